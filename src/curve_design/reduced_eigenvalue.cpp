#include "fairshape/curve_design/reduced_eigenvalue.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "fairshape/curve_design/kkt_factor.h"
#include "fairshape/curve_design/length_manifold.h"

namespace fairshape {
namespace {

// The banded factor of [W − tI, Jᵀ; J, 0] at X with its multipliers fixed, asked for inertia.
class ShiftedKkt {
 public:
  ShiftedKkt(const LengthProblem& p, const MatrixX3& X, const Eigen::VectorXd& lambda)
      : X_(X), lambda_(lambda), rows_(p.rows(X)), n_(3 * p.n_points()), m_(p.n_constraint_rows()),
        kkt_(make_kkt_factor(p, kFastestBackend, KktMethod::Direct, 1e-13)) {}
  //! #{eigenvalues of Zᵀ W Z below t}, −1 when the factorization fails or gives no inertia.
  int count_below(double t) {
    ++factorizations;
    if (!kkt_->factor(X_, rows_, &lambda_, -t)) return -1;
    const int negative = kkt_->negative_pivots();
    return negative < 0 ? -1 : std::max(negative - m_, 0);
  }
  //! Inverse iteration with the factor of the last count_below(t), t below λ_min (Golub & Van
  //! Loan §8.2.2): each solve [W − tI, Jᵀ; J, 0][w; ·] = [v; 0] gives w = Z (Zᵀ(W − tI)Z)⁻¹ Zᵀ v,
  //! a tangent vector, so λ_min's eigenvector dominates. Empty on a failed solve.
  Eigen::VectorXd inverse_iteration(int iterations) {
    Eigen::VectorXd v(n_), rhs = Eigen::VectorXd::Zero(n_ + m_);
    for (int i = 0; i < n_; ++i) v[i] = std::sin(1.7 * i + 0.3) + 0.5 * std::cos(0.37 * i);  // deterministic start
    for (int k = 0; k < iterations; ++k) {
      rhs.head(n_) = v / v.norm();
      v = kkt_->solve(rhs).head(n_);
      if (!v.allFinite() || v.norm() == 0) return {};
    }
    return v / v.norm();
  }
  //! The largest eigenvalue of (Zᵀ(W − tI)Z)⁻¹ by Lanczos with full reorthogonalization (Golub &
  //! Van Loan §10.1) on the factor of the last count_below(t) = 0: a Ritz value, so ≤ the true
  //! one, and t + 1/θ ≥ λ_min is an upper bound. Stops when θ changes by less than `tolerance`
  //! (relative) or after `max_steps` solves; 0 on a failed solve.
  double lanczos_largest(int max_steps, double tolerance) {
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n_ + m_);
    const auto apply = [&](const Eigen::VectorXd& v) {
      rhs.head(n_) = v;
      return Eigen::VectorXd(kkt_->solve(rhs).head(n_));
    };
    Eigen::VectorXd start(n_);
    for (int i = 0; i < n_; ++i) start[i] = std::sin(1.7 * i + 0.3) + 0.5 * std::cos(0.37 * i);  // deterministic
    Eigen::VectorXd q = apply(start);  // into the tangent space, where the operator lives
    if (!q.allFinite() || q.norm() == 0) return 0;
    Eigen::MatrixXd Q(n_, max_steps);
    Eigen::VectorXd alpha(max_steps), beta(max_steps);
    Q.col(0) = q / q.norm();
    double theta = 0;
    for (int k = 0; k < max_steps; ++k) {
      Eigen::VectorXd w = apply(Q.col(k));
      if (!w.allFinite()) return 0;
      alpha[k] = Q.col(k).dot(w);
      for (int pass = 0; pass < 2; ++pass) w -= Q.leftCols(k + 1) * (Q.leftCols(k + 1).transpose() * w);
      beta[k] = w.norm();
      Eigen::MatrixXd T = Eigen::MatrixXd::Zero(k + 1, k + 1);
      for (int i = 0; i <= k; ++i) {
        T(i, i) = alpha[i];
        if (i < k) T(i, i + 1) = T(i + 1, i) = beta[i];
      }
      const double next = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(T, Eigen::EigenvaluesOnly).eigenvalues()(k);
      const bool settled = std::abs(next - theta) <= tolerance * next;
      theta = next;
      if (settled || k + 1 == max_steps || beta[k] <= 1e-14 * theta) break;
      Q.col(k + 1) = w / beta[k];
    }
    return theta;
  }
  int factorizations = 0;

 private:
  const MatrixX3& X_;
  const Eigen::VectorXd& lambda_;
  std::vector<ConstraintRow> rows_;
  int n_, m_;
  std::unique_ptr<KktFactor> kkt_;
};

// Gershgorin's bound on W's spectrum (W symmetric, stored in full): Zᵀ W Z's eigenvalues lie
// inside W's range (Cauchy interlacing), so max |λ| ≤ max_i Σ_j |W_ij|.
double gershgorin_bound(const SparseMatrix& W) {
  double bound = 0;
  for (int k = 0; k < W.outerSize(); ++k) {
    double sum = 0;
    for (SparseMatrix::InnerIterator it(W, k); it; ++it) sum += std::abs(it.value());
    bound = std::max(bound, sum);
  }
  return bound;
}

// Inverse-iteration steps of the one acceleration (a Rayleigh quotient is an upper bound).
constexpr int kRayleighSteps = 4;
// Lanczos steps at most (each one banded solve, a tenth of a factorization's cost).
constexpr int kLanczosSteps = 12;

}  // namespace

ReducedEigenvalueBracket smallest_reduced_eigenvalue(const LengthProblem& p, const MatrixX3& X, double relative_tolerance) {
  ReducedEigenvalueBracket out;
  const Eigen::VectorXd lambda = least_squares_multipliers(p, X);
  if (!lambda.allFinite()) return out;
  const SparseMatrix W = lagrangian_hessian(p, X, lambda);
  out.scale = std::max(gershgorin_bound(W), 1e-300);
  const double floor = kReducedEigenvalueFloor * out.scale;
  ShiftedKkt kkt(p, X, lambda);
  // λ_min ∈ [lo, hi], count_below(lo) = 0 ≤ count_below(hi) − 1 kept throughout. The sign first
  // (one factorization at 0), then geometric steps in |λ| while the bracket spans orders of
  // magnitude (a tiny eigenvalue of a soft curve in log log steps), arithmetic ones within a
  // factor of two — after one Rayleigh quotient from the lower end, an upper bound that usually
  // closes the bracket at once (the quotient of a tangent vector is ≥ λ_min).
  double lo = -out.scale, hi = out.scale;
  const auto probe = [&](double t) {
    const int below = kkt.count_below(t);
    if (below < 0) return false;
    (below > 0 ? hi : lo) = t;
    return true;
  };
  if (!probe(0)) return out;
  // A positive semidefinite reduced Hessian (every minimum): its factor at 0 serves Lanczos on
  // the inverse, whose Ritz value gives an upper bound close to λ_min in a few solves; one more
  // factorization just below it confirms the lower end, so a minimum costs two factorizations.
  // Bisection is the fallback (and the way at a saddle, where no factor is definite yet).
  if (lo == 0) {
    const double theta = kkt.lanczos_largest(kLanczosSteps, 0.3 * relative_tolerance);
    if (theta > 0 && 1 / theta < hi) {
      hi = 1 / theta;
      // Just below the Ritz bound, then (a Ritz value of a cluster converges slowly) walking down
      // in doubling steps until a probe has no eigenvalue below it: usually one or two probes.
      const double rho = hi;
      for (double step = 0.9 * std::max(relative_tolerance * rho, floor); rho - step > lo; step *= 2) {
        const double t = rho - step;
        if (!probe(t)) return out;
        if (lo == t) break;
      }
    }
  }
  bool accelerated = false;
  while (hi - lo > std::max(relative_tolerance * std::max(std::abs(lo), std::abs(hi)), floor)) {
    const double sign = lo >= 0 ? 1 : -1;
    const double a = sign > 0 ? lo : -hi, b = sign > 0 ? hi : -lo;  // |λ_min| ∈ [a, b]
    if (a == 0 && b <= floor) break;  // rounding: |λ_min| below the floor
    if (a > 0 && b <= 2 * a && !accelerated) {
      accelerated = true;
      if (!probe(lo)) return out;  // refactor at the lower end: W − lo·I positive definite on the tangent space
      const Eigen::VectorXd v = kkt.inverse_iteration(kRayleighSteps);
      if (v.size() > 0) {
        const double rayleigh = v.dot(W * v);
        if (rayleigh < hi && rayleigh > lo) {
          hi = rayleigh;
          const double t = hi - 0.5 * std::max(relative_tolerance * std::abs(hi), floor);
          if (t > lo && !probe(t)) return out;
        }
      }
      continue;
    }
    const double m = a == 0 ? std::sqrt(floor * b) : (b > 2 * a ? std::sqrt(a * b) : 0.5 * (a + b));
    if (!probe(sign * m)) return out;
  }
  out.ok = true;
  out.lower = lo;
  out.upper = hi;
  out.factorizations = kkt.factorizations;
  return out;
}

MatrixX3 smallest_reduced_eigenvector(const LengthProblem& p, const MatrixX3& X, const ReducedEigenvalueBracket& bracket,
                                      int iterations) {
  if (!bracket.ok) return {};
  const Eigen::VectorXd lambda = least_squares_multipliers(p, X);
  if (!lambda.allFinite()) return {};
  ShiftedKkt kkt(p, X, lambda);
  const double gap = std::max(bracket.upper - bracket.lower, kReducedEigenvalueFloor * bracket.scale);
  if (kkt.count_below(bracket.lower - gap) != 0) return {};  // W − μI not positive definite on the tangent space
  const Eigen::VectorXd v = kkt.inverse_iteration(iterations);
  if (v.size() == 0) return {};
  return Eigen::Map<const MatrixX3>(v.data(), p.n_points(), 3);
}

}  // namespace fairshape
