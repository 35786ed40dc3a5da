#include "fairshape/problem/constrained_system.h"

#include "fairshape/core/error.h"

namespace fairshape {

ReducedSystem reduce(const ConstrainedSystem& s) { return reduce(s.H, s.g, s.fixed, s.fixed_values); }

ReducedSystem reduce(const SparseMatrix& H, const Eigen::MatrixXd& g, const std::vector<int>& fixed,
                     const Eigen::MatrixXd& fixed_values) {
  const int n = static_cast<int>(H.rows());
  if (H.cols() != n || g.rows() != n)
    throw InvalidInput("reduce: H is " + std::to_string(H.rows()) + "×" + std::to_string(H.cols()) +
                       " but g has " + std::to_string(g.rows()) + " rows");
  if (static_cast<Eigen::Index>(fixed.size()) != fixed_values.rows())
    throw InvalidInput("reduce: fixed ids and fixed values differ in count");
  if (!fixed_values.allFinite() || !g.allFinite())
    throw InvalidInput("reduce: constraint targets or right-hand side are not finite");
  ReducedSystem r;
  r.n_full = n;
  r.fixed = fixed;
  std::vector<int> slot(n, -1);  // index among free unknowns, or -1 for fixed
  std::vector<char> is_fixed(n, 0);
  for (int v : fixed) {
    if (v < 0 || v >= n) throw InvalidInput("reduce: fixed vertex " + std::to_string(v) + " out of range");
    is_fixed[v] = 1;
  }
  for (int v = 0; v < n; ++v)
    if (!is_fixed[v]) {
      slot[v] = static_cast<int>(r.free.size());
      r.free.push_back(v);
    }
  // H_ff and H_fc column by column straight from H's columns (slots grow with the vertex id, so
  // each column's rows stay sorted): no triplet list, which at 4.5M unknowns held 2 GB more
  // than the matrices it built.
  const auto n_free = static_cast<Eigen::Index>(r.free.size());
  // A source column of −1 is empty.
  const auto columns_of = [&](SparseMatrix& out, const std::vector<int>& source_columns) {
    Eigen::VectorXi sizes(static_cast<Eigen::Index>(source_columns.size()));
    for (std::size_t k = 0; k < source_columns.size(); ++k) {
      int count = 0;
      if (source_columns[k] >= 0)
        for (SparseMatrix::InnerIterator it(H, source_columns[k]); it; ++it) count += slot[it.row()] >= 0;
      sizes[static_cast<Eigen::Index>(k)] = count;
    }
    out.resize(n_free, static_cast<Eigen::Index>(source_columns.size()));
    // Eigen's makeCompressed reads one entry past a zero-column uncompressed matrix (ASan).
    if (source_columns.empty()) return;
    out.reserve(sizes);
    for (std::size_t k = 0; k < source_columns.size(); ++k)
      if (source_columns[k] >= 0)
        for (SparseMatrix::InnerIterator it(H, source_columns[k]); it; ++it)
          if (slot[it.row()] >= 0) out.insertBackUncompressed(slot[it.row()], static_cast<Eigen::Index>(k)) = it.value();
    out.makeCompressed();
  };
  columns_of(r.A, r.free);
  // A vertex listed twice couples through its last listing (its value is that one's).
  std::vector<int> last_listing(static_cast<std::size_t>(n), -1), coupled(fixed);
  for (std::size_t k = 0; k < fixed.size(); ++k) last_listing[static_cast<std::size_t>(fixed[k])] = static_cast<int>(k);
  for (std::size_t k = 0; k < fixed.size(); ++k)
    if (last_listing[static_cast<std::size_t>(fixed[k])] != static_cast<int>(k)) coupled[k] = -1;
  columns_of(r.coupling, coupled);
  r.g_free = r.restrict_to_free(g);
  r.set_fixed_values(fixed_values);
  return r;
}

void ReducedSystem::set_fixed_values(const Eigen::MatrixXd& values) {
  const bool none = fixed.empty() && values.size() == 0;
  if (!none && (values.rows() != static_cast<Eigen::Index>(fixed.size()) || values.cols() != g_free.cols() || !values.allFinite()))
    throw InvalidInput("reduce: " + std::to_string(values.rows()) + " fixed values for " + std::to_string(fixed.size()) +
                       " fixed unknowns, or a value is not finite");
  fixed_values = values;
  b = none ? g_free : Eigen::MatrixXd(g_free - coupling * values);
}

Eigen::MatrixXd ReducedSystem::expand(const Eigen::MatrixXd& u_free, const Eigen::MatrixXd& values) const {
  Eigen::MatrixXd u(n_full, u_free.cols());
  for (std::size_t i = 0; i < free.size(); ++i) u.row(free[i]) = u_free.row(static_cast<Eigen::Index>(i));
  for (std::size_t k = 0; k < fixed.size(); ++k) u.row(fixed[k]) = values.row(static_cast<Eigen::Index>(k));
  return u;
}

Eigen::MatrixXd ReducedSystem::restrict_to_free(const Eigen::MatrixXd& u_full) const {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(free.size()), u_full.cols());
  for (std::size_t i = 0; i < free.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = u_full.row(free[i]);
  return out;
}

double quadratic_energy(const SparseMatrix& H, const Eigen::MatrixXd& g, const Eigen::MatrixXd& u) {
  return 0.5 * (u.transpose() * (H * u)).trace() - (g.transpose() * u).trace();
}

double relative_error(const Eigen::MatrixXd& x, const Eigen::MatrixXd& reference) {
  const double scale = reference.norm() > 0 ? reference.norm() : 1.0;
  return (x - reference).norm() / scale;
}

double relative_residual(const SparseMatrix& A, const Eigen::MatrixXd& b, const Eigen::MatrixXd& x) {
  const double r = (b - A * x).norm(), nb = b.norm();
  return nb > 0 ? r / nb : r;
}

SparseMatrix stack_rows(const std::vector<const SparseMatrix*>& blocks) {
  FAIRSHAPE_ASSERT(!blocks.empty(), "stack_rows needs a block");
  Triplets t;
  Eigen::Index rows = 0;
  for (const SparseMatrix* b : blocks) {
    FAIRSHAPE_ASSERT(b->cols() == blocks.front()->cols(), "stacked blocks differ in columns");
    for (int c = 0; c < b->outerSize(); ++c)
      for (SparseMatrix::InnerIterator it(*b, c); it; ++it) t.emplace_back(static_cast<int>(rows + it.row()), c, it.value());
    rows += b->rows();
  }
  SparseMatrix out(rows, blocks.front()->cols());
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

SparseMatrix block_diagonal(const SparseMatrix& M, int copies) {
  if (copies == 1) return M;
  Triplets t;
  t.reserve(static_cast<std::size_t>(copies) * M.nonZeros());
  for (int d = 0; d < copies; ++d)
    for (int c = 0; c < M.outerSize(); ++c)
      for (SparseMatrix::InnerIterator it(M, c); it; ++it)
        t.emplace_back(static_cast<int>(d * M.rows() + it.row()), static_cast<int>(d * M.cols() + c), it.value());
  SparseMatrix out(copies * M.rows(), copies * M.cols());
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

}  // namespace fairshape
