#include "fairshape/curve_design/subspace_step.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace fairshape {
namespace {

// Modified Gram–Schmidt, twice ("twice is enough": Giraud, Langou, Rozložník 2005), dropping
// columns whose norm falls below `drop` of what they had: the block may lose rank when two
// columns converge to the same eigenvector.
Eigen::MatrixXd orthonormal_columns(const Eigen::MatrixXd& A, double drop = 1e-10) {
  Eigen::MatrixXd Q(A.rows(), A.cols());
  Eigen::Index kept = 0;
  for (Eigen::Index j = 0; j < A.cols(); ++j) {
    Eigen::VectorXd v = A.col(j);
    const double before = v.norm();
    if (!(before > 0) || !v.allFinite()) continue;
    for (int pass = 0; pass < 2; ++pass)
      for (Eigen::Index i = 0; i < kept; ++i) v -= Q.col(i).dot(v) * Q.col(i);
    const double after = v.norm();
    if (after <= drop * before) continue;
    Q.col(kept++) = v / after;
  }
  return Q.leftCols(kept);
}

// |(Λ + μ)⁻¹ γ| over the components not in `skip` (the hard case's eigenspace).
double step_norm(const Eigen::VectorXd& lambda, const Eigen::VectorXd& gamma, double mu, Eigen::Index skip = 0) {
  double s = 0;
  for (Eigen::Index i = skip; i < lambda.size(); ++i) s += std::pow(gamma[i] / (lambda[i] + mu), 2);
  return std::sqrt(s);
}

}  // namespace

SmallTrustRegionStep solve_small_trust_region(const Eigen::MatrixXd& H, const Eigen::VectorXd& g, double radius,
                                              const Eigen::MatrixXd* basis) {
  SmallTrustRegionStep out;
  const Eigen::Index k = H.rows();
  out.c = Eigen::VectorXd::Zero(k);
  if (k == 0 || !(radius > 0)) return out;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (H + H.transpose()));
  const Eigen::VectorXd& lambda = eig.eigenvalues();  // ascending
  const Eigen::MatrixXd& U = eig.eigenvectors();
  const Eigen::VectorXd gamma = U.transpose() * g;
  const double scale = std::max(lambda.cwiseAbs().maxCoeff(), 1e-300);
  const double l1 = lambda[0];
  out.negative_curvature = l1 < -1e-12 * scale;
  Eigen::VectorXd coeff(k);  // in the eigenbasis
  if (l1 > 1e-12 * scale && step_norm(lambda, gamma, 0) <= radius) {
    coeff = -gamma.cwiseQuotient(lambda);  // interior Newton step of a convex model
  } else {
    // The boundary: μ ≥ max(0, −λ₁) with |(Λ + μ)⁻¹γ| = Δ. Hard case: g has (to rounding) no
    // component on λ₁'s eigenspace, so no such μ > −λ₁ exists; then μ = −λ₁ and u₁ fills Δ.
    const double floor = std::max(0.0, -l1);
    Eigen::Index degenerate = 0;
    while (degenerate < k && lambda[degenerate] - l1 <= 1e-12 * scale) ++degenerate;
    const double gnorm = gamma.norm();
    const bool hard = out.negative_curvature && gamma.head(degenerate).norm() <= 1e-10 * std::max(gnorm, 1e-300) &&
                      step_norm(lambda, gamma, floor, degenerate) <= radius;
    if (hard) {
      coeff.setZero();
      for (Eigen::Index i = degenerate; i < k; ++i) coeff[i] = -gamma[i] / (lambda[i] + floor);
      // Either side of u₁ is as good (g has no component on it: a planar curve's out-of-plane
      // mode, say): the side of the lifted vector's largest entry, so both back ends and every
      // run take the same one.
      const Eigen::VectorXd u1 = basis ? Eigen::VectorXd(*basis * U.col(0)) : Eigen::VectorXd(U.col(0));
      Eigen::Index largest = 0;
      u1.cwiseAbs().maxCoeff(&largest);
      coeff[0] = std::copysign(std::sqrt(std::max(radius * radius - coeff.squaredNorm(), 0.0)), u1[largest]);
    } else {
      // Bisection on the secular equation |(Λ + μ)⁻¹γ| = Δ, decreasing in μ on (−λ₁, ∞):
      // hi = max(0, −λ₁) + |γ|/Δ gives a norm ≤ Δ. Robust and cheap at this size.
      double lo = floor, hi = floor + gnorm / radius + 1e-300;
      for (int it = 0; it < 200 && hi - lo > 1e-15 * std::max(hi, 1e-300); ++it) {
        const double mid = 0.5 * (lo + hi);
        (step_norm(lambda, gamma, mid) > radius ? lo : hi) = mid;
      }
      coeff = -gamma.cwiseQuotient((lambda.array() + hi).matrix());
    }
    out.on_boundary = true;
  }
  out.c = U * coeff;
  out.model = g.dot(out.c) + 0.5 * out.c.dot(H * out.c);
  return out;
}

RitzPairs block_inverse_iteration(KktFactor& shifted, const SparseMatrix& W, Eigen::MatrixXd& block, int n_constraints,
                                  int steps) {
  RitzPairs out;
  const Eigen::Index n = block.rows();
  Eigen::MatrixXd V = orthonormal_columns(block);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + n_constraints);
  for (int step = 0; step < steps && V.cols() > 0; ++step) {
    Eigen::MatrixXd next(n, V.cols());
    for (Eigen::Index j = 0; j < V.cols(); ++j) {
      rhs.head(n) = V.col(j);
      next.col(j) = shifted.solve(rhs).head(n);
      ++out.solves;
    }
    V = orthonormal_columns(next);
  }
  block = V;
  if (V.cols() == 0) return out;
  // Rayleigh–Ritz: the eigenpairs of Vᵀ W V, lifted.
  const Eigen::MatrixXd WV = W * V;
  const Eigen::MatrixXd H = V.transpose() * WV;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (H + H.transpose()));
  out.values = eig.eigenvalues();
  out.vectors = V * eig.eigenvectors();
  return out;
}

Eigen::MatrixXd initial_block(int n, int k) {
  Eigen::MatrixXd B(n, k);
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < n; ++i)
      B(i, j) = std::sin((1.7 + 0.61 * j) * i + 0.3 * (j + 1)) + 0.5 * std::cos((0.37 + 0.13 * j) * i);
  return B;
}

SubspaceStep subspace_trust_region_step(const Eigen::MatrixXd& basis, const SparseMatrix& W, const Eigen::VectorXd& g,
                                        double radius) {
  SubspaceStep out;
  const Eigen::MatrixXd S = orthonormal_columns(basis);
  out.s = Eigen::VectorXd::Zero(basis.rows());
  if (S.cols() == 0) return out;
  const Eigen::MatrixXd WS = W * S;
  const Eigen::MatrixXd H = S.transpose() * WS;
  const Eigen::VectorXd gs = S.transpose() * g;
  const SmallTrustRegionStep small = solve_small_trust_region(H, gs, radius, &S);
  out.s = S * small.c;
  out.predicted = -(g.dot(out.s) + 0.5 * out.s.dot(W * out.s));
  out.negative_curvature = small.negative_curvature;
  out.on_boundary = small.on_boundary;
  return out;
}

}  // namespace fairshape
