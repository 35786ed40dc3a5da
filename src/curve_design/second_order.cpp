#include "fairshape/curve_design/second_order.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <sstream>

#include "fairshape/core/message_format.h"
#include "fairshape/curve_design/kkt_factor.h"
#include "fairshape/curve_design/length_manifold.h"
#include "fairshape/curve_design/reduced_eigenvalue.h"

namespace fairshape {

SecondOrderCheck check_second_order(const LengthProblem& p, const MatrixX3& X) {
  SecondOrderCheck out;
  const int N = p.n_points(), n = 3 * N;
  if (N > kSecondOrderDenseLimit) {
    out.message = "second-order check skipped: " + std::to_string(N) + " points (dense limit " +
                  std::to_string(kSecondOrderDenseLimit) + ")";
    return out;
  }
  const std::vector<ConstraintRow> rows = p.rows(X);
  const Eigen::MatrixXd J = Eigen::MatrixXd(constraint_jacobian(rows, N));  // m × 3N, interleaved
  // λ: least squares of ∇F + Jᵀλ = 0 (interleaved like J's columns).
  const MatrixX3 G = p.objective_gradient(X);
  Eigen::VectorXd g(n);
  for (int i = 0; i < N; ++i)
    for (int c = 0; c < 3; ++c) g[3 * i + c] = G(i, c);
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr_jt(J.transpose());
  const Eigen::VectorXd lambda = qr_jt.solve(-g);
  const SparseMatrix W = lagrangian_hessian(p, X, lambda);
  // Z: the last n − rank columns of the full Q factor of Jᵀ.
  const Eigen::Index rank = qr_jt.rank();
  const Eigen::MatrixXd Qfull = qr_jt.householderQ();
  const Eigen::MatrixXd Z = Qfull.rightCols(n - rank);
  if (Z.cols() == 0) {
    out.checked = true;
    out.message = "no free directions: the constraints determine the curve";
    return out;
  }
  const Eigen::MatrixXd reduced = Z.transpose() * (W * Z);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (reduced + reduced.transpose()));
  out.checked = true;
  out.min_eigenvalue = eig.eigenvalues()(0);
  out.max_abs_eigenvalue = eig.eigenvalues().cwiseAbs().maxCoeff();
  const Eigen::VectorXd d = Z * eig.eigenvectors().col(0);
  out.direction.resize(N, 3);
  for (int i = 0; i < N; ++i)
    for (int c = 0; c < 3; ++c) out.direction(i, c) = d[3 * i + c];
  out.message = "reduced Hessian eigenvalues in [" + sci(out.min_eigenvalue) + ", " + sci(eig.eigenvalues()(eig.eigenvalues().size() - 1)) +
                "] on " + std::to_string(Z.cols()) + " free directions";
  return out;
}

int reduced_hessian_negative_count(const LengthProblem& p, const MatrixX3& X, double shift) {
  const Eigen::VectorXd lambda = least_squares_multipliers(p, X);
  if (!lambda.allFinite()) return -1;
  const auto kkt = make_kkt_factor(p, kFastestBackend, KktMethod::Direct, 1e-13);
  if (shift < 0) shift = kSecondOrderTolerance * p.objective_hessian().diagonal().cwiseAbs().maxCoeff();
  if (!kkt->factor(X, p.rows(X), &lambda, shift)) return -1;
  const int negative = kkt->negative_pivots();
  return negative < 0 ? -1 : std::max(negative - p.n_constraint_rows(), 0);
}

const char* to_string(SecondOrderMode mode) {
  switch (mode) {
    case SecondOrderMode::Inertia: return "inertia";
    case SecondOrderMode::Dense: return "dense";
    case SecondOrderMode::Off: return "off";
  }
  return "?";
}

SecondOrderCheck check_second_order_by_inertia(const LengthProblem& p, const MatrixX3& X, bool want_direction) {
  SecondOrderCheck out;
  const ReducedEigenvalueBracket b = smallest_reduced_eigenvalue(p, X);
  // A bracket at or above −shift already says "none below it"; only a lower one needs the count.
  const double shift = kSecondOrderTolerance * p.objective_hessian().diagonal().cwiseAbs().maxCoeff();
  out.negative_count = b.ok && b.lower >= -shift ? 0 : reduced_hessian_negative_count(p, X, shift);
  if (out.negative_count < 0 || !b.ok) {
    out.negative_count = -1;
    out.message = "second order not checked: the KKT factorization failed or gave no inertia";
    return out;
  }
  out.checked = true;
  out.min_eigenvalue = b.estimate();
  out.min_eigenvalue_error = 0.5 * (b.upper - b.lower);
  out.max_abs_eigenvalue = b.scale;
  if (out.negative_count > 0 && want_direction) out.direction = smallest_reduced_eigenvector(p, X, b);
  std::ostringstream m;
  m << "reduced Hessian's smallest eigenvalue in [" << sci(b.lower) << ", " << sci(b.upper) << "] (inertia bisection, "
    << b.factorizations << " banded factorizations), " << out.negative_count << " below the shift (LDLT inertia)";
  out.message = m.str();
  return out;
}

SecondOrderCheck second_order_check(const LengthProblem& p, const MatrixX3& X, SecondOrderMode mode, bool want_direction) {
  if (mode == SecondOrderMode::Off) {
    SecondOrderCheck off;
    off.message = "second order not checked (second_order: off)";
    return off;
  }
  if (mode == SecondOrderMode::Dense && p.n_points() <= kSecondOrderDenseLimit) return check_second_order(p, X);
  SecondOrderCheck out = check_second_order_by_inertia(p, X, want_direction);
  if (mode == SecondOrderMode::Dense) {
    std::ostringstream m;
    m << out.message << "; dense check not made: " << p.n_points() << " points (dense limit " << kSecondOrderDenseLimit << ")";
    out.message = m.str();
  }
  return out;
}

SecondOrderCheck judge_second_order(const LengthProblem& p, LengthSolveReport& rep, bool stationarity_asked, SecondOrderMode mode,
                                    const SecondOrderCheck* made) {
  // Lengths alone (the paper's rule) claim no optimality: the eigenvalue is only reported, so
  // it is not paid for above the dense limit (a point away from stationarity usually has an
  // indefinite reduced Hessian, where the bracket falls back to bisection: many factorizations).
  if (!made && !stationarity_asked && mode == SecondOrderMode::Inertia && p.n_points() > kSecondOrderDenseLimit) {
    std::ostringstream m;
    m << "; lengths alone (stationarity_tolerance 0): second order not estimated above " << kSecondOrderDenseLimit << " points";
    rep.summary.message += m.str();
    return {};
  }
  SecondOrderCheck so = made ? *made : second_order_check(p, rep.points, mode, false);
  if (!so.checked) {
    rep.summary.message += "; " + so.message;
    return so;
  }
  rep.min_reduced_hessian_eig = so.min_eigenvalue;
  if (!stationarity_asked) {
    // Lengths alone (the paper's rule): the point claims no optimality, so its curvature is
    // reported, not judged — least-squares λ away from a stationary point say little.
    rep.summary.message += "; lengths alone (stationarity_tolerance 0): reduced Hessian's smallest eigenvalue " +
                           sci(so.min_eigenvalue) + " reported, not judged";
    return so;
  }
  if (!so.is_minimum(kSecondOrderTolerance)) {
    rep.summary.termination = Termination::NotAMinimum;
    rep.summary.message = so.negative_count >= 0
                              ? "stationary but not a minimum: " + so.message + ", a constrained saddle"
                              : "stationary but not a minimum: the reduced Hessian's smallest eigenvalue is " + sci(so.min_eigenvalue) +
                                    " (largest |eigenvalue| " + sci(so.max_abs_eigenvalue) + "), a constrained saddle";
  } else if (so.negative_count >= 0) {
    rep.summary.message += "; " + so.message;
  }
  return so;
}

}  // namespace fairshape
