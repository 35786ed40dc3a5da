#include "fairshape/energy/local_quadratic.h"
#include "fairshape/energy/ring_coupling.h"

#if FAIRSHAPE_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#endif

#include <cmath>

#include "fairshape/energy/divided_differences.h"
#include "fairshape/energy/gram_assembly.h"

namespace fairshape {

Eigen::Vector<double, 5> term_weights(const StretchBendWeights& w, double scale) {
  return 2.0 * scale * Eigen::Vector<double, 5>(w.alpha, w.alpha, w.beta, 2.0 * w.beta, w.beta);
}

// G: 5 × (1 + |R|), rows g_m over (v, ring...): g_m[v] = −Σ_j D_mj, g_m[ring j] = D_mj.
Eigen::MatrixXd difference_rows(const LocalFit& fit) {
  const auto n = static_cast<Eigen::Index>(fit.ring.size());
  Eigen::MatrixXd G(5, n + 1);
  G.col(0) = -fit.D.rowwise().sum();
  G.rightCols(n) = fit.D;
  return G;
}

std::vector<int> stencil(int v, const LocalFit& fit) {
  std::vector<int> ids{v};
  ids.insert(ids.end(), fit.ring.begin(), fit.ring.end());
  return ids;
}

// At a vertex on a sharp crease the energy is the weighted sum over the sectors the crease
// separates (sector_fits): no divided difference reaches across the crease.
void add_vertex_block(const SurfaceMesh& mesh, int v, const StretchBendWeights& w, double scale, Triplets& out) {
  if (mesh.is_isolated(v)) return;
  for (const LocalFit& fit : sector_fits(mesh, v)) {
    const int n = static_cast<int>(fit.ring.size());
    const Eigen::MatrixXd G = difference_rows(fit);
    const Eigen::MatrixXd block = G.transpose() * term_weights(w, scale * fit.weight).asDiagonal() * G;
    const std::vector<int> ids = stencil(v, fit);
    for (int a = 0; a <= n; ++a)
      for (int b = 0; b <= n; ++b) out.emplace_back(ids[a], ids[b], block(a, b));
  }
}

void add_stretch_bend_hessian(const SurfaceMesh& mesh, const StretchBendWeights& w, double scale, Triplets& out,
                              Backend backend) {
  check_ring_coupling(mesh, "stretch + bend energy");
  require_backend(backend);
  const int nv = mesh.n_vertices();
  if (backend == Backend::Reference) {
    for (int v = 0; v < nv; ++v) add_vertex_block(mesh, v, w, scale, out);
    return;
  }
#if FAIRSHAPE_WITH_TBB
  constexpr int kChunk = 1024;
  const int chunks = (nv + kChunk - 1) / kChunk;
  std::vector<Triplets> parts(chunks);
  tbb::parallel_for(tbb::blocked_range<int>(0, chunks, 1), [&](const tbb::blocked_range<int>& r) {
    for (int c = r.begin(); c != r.end(); ++c)
      for (int v = c * kChunk; v < std::min(nv, (c + 1) * kChunk); ++v) add_vertex_block(mesh, v, w, scale, parts[c]);
  });
  for (auto& p : parts) out.insert(out.end(), p.begin(), p.end());  // chunk order: deterministic
#endif
}

SparseMatrix stretch_bend_hessian(const SurfaceMesh& mesh, const StretchBendWeights& w, double scale,
                                  Backend backend) {
  check_ring_coupling(mesh, "stretch + bend energy");
  require_backend(backend);
#if FAIRSHAPE_WITH_TBB
  if (backend == Backend::Optimized) {
    // Fits in parallel chunks (each its own flat factor list, joined in chunk order), then
    // the rows of H gathered in parallel: no triplets, no serial sort.
    const int nv = mesh.n_vertices();
    constexpr int kChunk = 2048;
    const int chunks = (nv + kChunk - 1) / kChunk;
    std::vector<GramFactors> parts(chunks);
    tbb::parallel_for(tbb::blocked_range<int>(0, chunks, 1), [&](const tbb::blocked_range<int>& r) {
      for (int c = r.begin(); c != r.end(); ++c) {
        parts[c].k = 5;
        for (int v = c * kChunk; v < std::min(nv, (c + 1) * kChunk); ++v) {
          if (mesh.is_isolated(v)) continue;
          for (const LocalFit& fit : sector_fits(mesh, v)) {
            // A sector's share ω enters the Gram matrix as (√ω G)ᵀ W (√ω G).
            if (fit.weight == 1.0) parts[c].append(stencil(v, fit), difference_rows(fit));
            else parts[c].append(stencil(v, fit), std::sqrt(fit.weight) * difference_rows(fit));
          }
        }
      }
    });
    // Joined into one list sized once, each part freed as soon as it is copied: appending
    // into a growing list while every part stayed alive held up to three times the factors
    // (about 7 GB of them at 17.8M vertices, where that join ran the process out of memory).
    GramFactors all;
    all.k = 5;
    std::size_t entries = 0, stencils = 0;
    for (const auto& p : parts) entries += p.ids.size(), stencils += p.offset.size() - 1;
    all.ids.reserve(entries);
    all.factor.reserve(entries * static_cast<std::size_t>(all.k));
    all.offset.reserve(stencils + 1);
    for (auto& p : parts) {
      all.append(p);
      p = GramFactors();
    }
    return assemble_gram(nv, all, term_weights(w, scale));
  }
#endif
  Triplets t;
  add_stretch_bend_hessian(mesh, w, scale, t, backend);
  SparseMatrix H(mesh.n_vertices(), mesh.n_vertices());
  H.setFromTriplets(t.begin(), t.end());
  return H;
}

}  // namespace fairshape
