#include "fairshape/energy/gram_assembly.h"

#include <algorithm>
#include <numeric>

#include "fairshape/core/error.h"
#include "fairshape/core/parallel_row_assembly.h"

namespace fairshape {

void GramFactors::append(const std::vector<int>& stencil, const Eigen::MatrixXd& G) {
  FAIRSHAPE_ASSERT(G.rows() == k && G.cols() == static_cast<Eigen::Index>(stencil.size()), "Gram factor size");
  ids.insert(ids.end(), stencil.begin(), stencil.end());
  factor.insert(factor.end(), G.data(), G.data() + G.size());
  offset.push_back(static_cast<int>(ids.size()));
}

void GramFactors::append(const GramFactors& other) {
  const int base = offset.back();
  ids.insert(ids.end(), other.ids.begin(), other.ids.end());
  factor.insert(factor.end(), other.factor.begin(), other.factor.end());
  for (std::size_t v = 1; v < other.offset.size(); ++v) offset.push_back(base + other.offset[v]);
}

namespace {

// For every row i, the stencil entries (flat positions into ids) that name it, by stencil order.
void incidence(int n, const GramFactors& f, std::vector<int>& start, std::vector<int>& entries) {
  start.assign(static_cast<std::size_t>(n) + 1, 0);
  for (int id : f.ids) ++start[id + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  entries.resize(f.ids.size());
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (std::size_t e = 0; e < f.ids.size(); ++e) entries[fill[f.ids[e]]++] = static_cast<int>(e);
}

}  // namespace

SparseMatrix assemble_gram(int n, const GramFactors& f, const Eigen::VectorXd& weights) {
  FAIRSHAPE_ASSERT(weights.size() == f.k, "Gram weights size");
  std::vector<int> start, entries;
  incidence(n, f, start, entries);
  // The stencil each flat entry belongs to.
  std::vector<int> owner(f.ids.size());
  for (std::size_t v = 0; v + 1 < f.offset.size(); ++v)
    std::fill(owner.begin() + f.offset[v], owner.begin() + f.offset[v + 1], static_cast<int>(v));

  return assemble_symmetric_by_rows(n, 4096, [&](int i, const auto& add, bool values) {
    for (int p = start[i]; p < start[i + 1]; ++p) {
      const int e = entries[p], v = owner[e], first = f.offset[v], size = f.offset[v + 1] - first;
      const double* G = f.factor.data() + static_cast<std::size_t>(f.k) * first;
      const double* Ga = G + static_cast<std::size_t>(f.k) * (e - first);
      for (int b = 0; b < size; ++b) {
        double s = 0;
        if (values) {
          const double* Gb = G + static_cast<std::size_t>(f.k) * b;
          for (int m = 0; m < f.k; ++m) s += weights[m] * Ga[m] * Gb[m];
        }
        add(f.ids[first + b], s);
      }
    }
  });
}

}  // namespace fairshape
