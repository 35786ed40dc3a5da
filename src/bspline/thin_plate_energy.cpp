#include "fairshape/bspline/thin_plate_energy.h"

#include "fairshape/core/backend.h"
#if FAIRSHAPE_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#endif

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <string>

#include "fairshape/bspline/uniform_basis.h"
#include "fairshape/core/error.h"

namespace fairshape::bspline {

void validate(const TensionWeights& w) {
  const auto fail = [](const std::string& what) { throw InvalidInput("thin plate weights: " + what); };
  if (!w.alpha.allFinite() || !w.beta.allFinite()) fail("alpha and beta must be finite");
  if (std::abs(w.alpha(0, 1) - w.alpha(1, 0)) > 1e-14 * (1 + w.alpha.cwiseAbs().maxCoeff()))
    fail("alpha must be symmetric (alpha_12 = alpha_21)");
  if (std::abs(w.beta(0, 1) - w.beta(1, 0)) > 1e-14 * (1 + w.beta.cwiseAbs().maxCoeff()))
    fail("beta must be symmetric (beta_12 = beta_21)");
  if (Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(w.alpha).eigenvalues().minCoeff() < -1e-14)
    fail("alpha must be positive semi-definite (alpha_12^2 <= alpha_11 alpha_22, alpha_ii >= 0)");
  if ((w.beta.array() < 0).any()) fail("every beta_ij must be >= 0");
  // No energy at all: nothing decides the surface between the constraints (the KKT system is
  // singular).
  if (w.alpha.isZero(0) && w.beta.isZero(0)) fail("alpha and beta are both zero: no energy to minimize");
}

namespace {

// Each term of Q at one point is (cᵀ d)² for d = (w_u, w_v, w_uu, w_uv, w_vv): the rows c of
// the weight's square root. ½ pᵀHp = Σ_q W_q Σ_terms (cᵀ d_q)², so the rows of K carry √(2 W_q).
struct TermRows {
  std::vector<Eigen::Matrix<double, 5, 1>> rows;
};
TermRows term_rows(const TensionWeights& w) {
  TermRows t;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(w.alpha);
  for (int k = 0; k < 2; ++k) {
    const double lambda = eig.eigenvalues()(k);
    if (lambda <= 0) continue;
    Eigen::Matrix<double, 5, 1> c = Eigen::Matrix<double, 5, 1>::Zero();
    c.head<2>() = std::sqrt(lambda) * eig.eigenvectors().col(k);
    t.rows.push_back(c);
  }
  const double bending[3] = {w.beta(0, 0), 2 * w.beta(0, 1), w.beta(1, 1)};  // w_uv appears twice
  for (int k = 0; k < 3; ++k) {
    if (bending[k] <= 0) continue;
    Eigen::Matrix<double, 5, 1> c = Eigen::Matrix<double, 5, 1>::Zero();
    c(2 + k) = std::sqrt(bending[k]);
    t.rows.push_back(c);
  }
  return t;
}

double term_value(const Eigen::Matrix<double, 5, 1>& c, const BasisEntry& e) {
  return c(0) * e.du + c(1) * e.dv + c(2) * e.duu + c(3) * e.duv + c(4) * e.dvv;
}

// Quadrature points of one leaf cell: (u, v, weight·area).
struct CellPoint {
  double u, v, weight;
};
std::vector<CellPoint> cell_points(const SpanId& c, const GaussRule& g) {
  const double h = std::ldexp(1.0, -c.level);
  std::vector<CellPoint> pts;
  for (std::size_t a = 0; a < g.nodes.size(); ++a)
    for (std::size_t b = 0; b < g.nodes.size(); ++b)
      pts.push_back({(c.i + g.nodes[a]) * h, (c.j + g.nodes[b]) * h, g.weights[a] * g.weights[b] * h * h});
  return pts;
}

SparseMatrix hessian_reference(const HierarchicalSurface& s, const TensionWeights& w) {
  // A plain transcription of eq. 5: H = 2 ∫ Σ α_ij D_i b ⊗ D_j b + β_ij D_iD_j b ⊗ D_iD_j b.
  const GaussRule g = gauss_legendre(s.degree() + 1);
  Triplets t;
  BasisRow row;
  for (const SpanId& cell : s.leaf_cells())
    for (const CellPoint& q : cell_points(cell, g)) {
      s.basis(q.u, q.v, row);
      for (const BasisEntry& a : row)
        for (const BasisEntry& b : row) {
          const double stretch = w.alpha(0, 0) * a.du * b.du + w.alpha(0, 1) * (a.du * b.dv + a.dv * b.du) +
                                 w.alpha(1, 1) * a.dv * b.dv;
          const double bend = w.beta(0, 0) * a.duu * b.duu + 2 * w.beta(0, 1) * a.duv * b.duv + w.beta(1, 1) * a.dvv * b.dvv;
          t.emplace_back(a.dof, b.dof, 2 * q.weight * (stretch + bend));
        }
    }
  SparseMatrix H(s.dof_count(), s.dof_count());
  H.setFromTriplets(t.begin(), t.end());
  return H;
}

// The rows of K on one leaf cell: every quadrature point reaches the same functions, in the
// same order, so the block is dense over `dofs`.
void cell_block(const HierarchicalSurface& s, const SpanId& cell, const GaussRule& g, const TermRows& terms, BasisRow& row,
                std::vector<int>& dofs, Eigen::MatrixXd& Kc) {
  const std::vector<CellPoint> pts = cell_points(cell, g);
  dofs.clear();
  for (std::size_t q = 0; q < pts.size(); ++q) {
    s.basis(pts[q].u, pts[q].v, row);
    if (q == 0) {
      for (const BasisEntry& e : row) dofs.push_back(e.dof);
      Kc.setZero(static_cast<Eigen::Index>(pts.size() * terms.rows.size()), static_cast<Eigen::Index>(dofs.size()));
    }
    FAIRSHAPE_ASSERT(row.size() == dofs.size(), "basis support changed inside a leaf cell");
    const double scale = std::sqrt(2 * pts[q].weight);
    for (std::size_t k = 0; k < terms.rows.size(); ++k)
      for (std::size_t e = 0; e < row.size(); ++e)
        Kc(static_cast<Eigen::Index>(q * terms.rows.size() + k), static_cast<Eigen::Index>(e)) = scale * term_value(terms.rows[k], row[e]);
  }
}

#if FAIRSHAPE_WITH_TBB  // the optimized back end
SparseMatrix hessian_optimized(const HierarchicalSurface& s, const TensionWeights& w) {
  const GaussRule g = gauss_legendre(s.degree() + 1);
  const TermRows terms = term_rows(w);
  const std::vector<SpanId> cells = s.leaf_cells();
  // One dense local matrix Kᵀ_cell K_cell per cell. A leaf cell at depth L meets (r+1)²
  // functions of every layer up to L, so its block has ((r+1)²(L+1))² entries: the triplets of
  // every cell at once grew as depth² × cells. Cells go in batches, each summed into H, so only
  // one batch's triplets are held (papers/welch-witkin/README.md, "Memory of deep refinement").
  constexpr std::size_t kBatch = 256;
  SparseMatrix H(s.dof_count(), s.dof_count());
  std::vector<Triplets> per_cell(std::min(kBatch, cells.size()));
  for (std::size_t start = 0; start < cells.size(); start += kBatch) {
    const std::size_t end = std::min(cells.size(), start + kBatch);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(start, end, 16), [&](const tbb::blocked_range<std::size_t>& range) {
      BasisRow row;
      Eigen::MatrixXd Kc, local;
      std::vector<int> dofs;
      for (std::size_t c = range.begin(); c != range.end(); ++c) {
        cell_block(s, cells[c], g, terms, row, dofs, Kc);
        local.noalias() = Kc.transpose() * Kc;
        Triplets& out = per_cell[c - start];
        out.clear();
        out.reserve(dofs.size() * dofs.size());
        for (std::size_t a = 0; a < dofs.size(); ++a)
          for (std::size_t b = 0; b < dofs.size(); ++b) out.emplace_back(dofs[a], dofs[b], local(a, b));
      }
    });
    std::size_t total = 0;
    for (std::size_t c = 0; c < end - start; ++c) total += per_cell[c].size();
    Triplets batch;
    batch.reserve(total);
    for (std::size_t c = 0; c < end - start; ++c) batch.insert(batch.end(), per_cell[c].begin(), per_cell[c].end());
    SparseMatrix part(s.dof_count(), s.dof_count());
    part.setFromTriplets(batch.begin(), batch.end());
    H += part;
  }
  return H;
}
#endif

}  // namespace

TensionWeights in_span_units(const TensionWeights& w, const Eigen::Vector2d& span_size) {
  // x_i = h_i u_i: D_{x_i} = D_{u_i} / h_i and dx dy = h_u h_v du dv.
  TensionWeights out;
  const double area = span_size.x() * span_size.y();
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      const double hij = span_size[i] * span_size[j];
      out.alpha(i, j) = w.alpha(i, j) * area / hij;
      out.beta(i, j) = w.beta(i, j) * area / (hij * hij);
    }
  return out;
}

SparseMatrix thin_plate_hessian(const HierarchicalSurface& s, const TensionWeights& design, Backend backend) {
  validate(design);
  const TensionWeights w = in_span_units(design, s.shape().span_size);
  require_backend(backend);
#if FAIRSHAPE_WITH_TBB
  return backend == Backend::Reference ? hessian_reference(s, w) : hessian_optimized(s, w);
#else
  return hessian_reference(s, w);
#endif
}

SparseMatrix thin_plate_square_root(const HierarchicalSurface& s, const TensionWeights& design) {
  validate(design);
  const TensionWeights w = in_span_units(design, s.shape().span_size);
  const GaussRule g = gauss_legendre(s.degree() + 1);
  const TermRows terms = term_rows(w);
  // Each cell's block (points × terms rows) is replaced by the R of its QR, which has the same
  // Kᵀ_cell K_cell with at most as many rows as the cell has functions: the stacked [μA; K]
  // the QR-penalty factors is 5x shorter for cubics.
  Triplets t;
  BasisRow row;
  Eigen::MatrixXd Kc;
  std::vector<int> dofs;
  Eigen::Index r = 0;
  for (const SpanId& cell : s.leaf_cells()) {
    cell_block(s, cell, g, terms, row, dofs, Kc);
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(Kc);
    const Eigen::Index rows = std::min(Kc.rows(), Kc.cols());
    const Eigen::MatrixXd R = qr.matrixQR().topRows(rows).triangularView<Eigen::Upper>();
    for (Eigen::Index i = 0; i < rows; ++i, ++r)
      for (Eigen::Index j = i; j < R.cols(); ++j)
        if (R(i, j) != 0) t.emplace_back(r, dofs[j], R(i, j));
  }
  SparseMatrix K(r, s.dof_count());
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

}  // namespace fairshape::bspline
