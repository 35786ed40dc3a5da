#include "fairshape/curve_design/length_manifold.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>

namespace fairshape {
namespace {

// 32 ulps of the largest coordinate against the shortest segment: a KKT solve and its
// refinement round each coordinate to a few ulps of the curve's extent, and a segment's
// relative error is that over its length (measured before: the Newton loop's attainable error
// was ≈ 4–40 n·ε on unit curves of 129 to 1M points). Figure 1's curve: 7e-13.
constexpr double kRoundingSafety = 32;

Eigen::Map<const Eigen::VectorXd> flat(const MatrixX3& X) { return {X.data(), X.size()}; }

}  // namespace

Eigen::VectorXd least_squares_multipliers(const LengthProblem& p, const MatrixX3& X) {
  const SparseMatrix J = constraint_jacobian(p.rows(X), p.n_points());
  const MatrixX3 G = p.objective_gradient(X);
  const SparseMatrix JJt = J * J.transpose();
  const Eigen::SimplicialLDLT<SparseMatrix> ldlt(JJt);
  if (ldlt.info() != Eigen::Success) return Eigen::VectorXd::Constant(J.rows(), std::nan(""));
  return ldlt.solve(-(J * flat(G)));
}

SparseMatrix lagrangian_hessian(const LengthProblem& p, const Eigen::VectorXd& lambda) {
  const int n = 3 * p.n_points();
  Triplets t;
  const SparseMatrix& Q = p.objective_hessian();
  for (int k = 0; k < Q.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(Q, k); it; ++it)
      for (int c = 0; c < 3; ++c) t.emplace_back(3 * static_cast<int>(it.row()) + c, 3 * static_cast<int>(it.col()) + c, it.value());
  p.add_constraint_hessians(lambda, t);
  SparseMatrix W(n, n);
  W.setFromTriplets(t.begin(), t.end());
  return W;
}

namespace {

// Gauss–Newton (Levenberg–Marquardt damped when a correction does not lower |g|) on the
// scaled rows g_r = (f_r(X) − offset_r) / scale_r, until max|g| ≤ g_tolerance and the
// relative length and pin errors (measured with the offset 0 only) are below `tolerance`.
Retraction gauss_newton(const LengthProblem& p, const MatrixX3& X, const Eigen::VectorXd& offset, double tolerance,
                        int max_iterations) {
  Retraction out;
  out.points = X;
  std::vector<ConstraintRow> rows = p.rows(X);
  const Eigen::Index m = static_cast<Eigen::Index>(rows.size());
  const bool homotopy = offset.cwiseAbs().maxCoeff() > 0;
  // Rows scaled to be dimensionless (segments: f / l² ≈ 2 δl / l, as Ceres's penalty uses them).
  Eigen::VectorXd inv_scale(m);
  for (Eigen::Index r = 0; r < m; ++r) inv_scale[r] = 1 / p.row_scale(static_cast<int>(r));
  const auto scaled = [&](const std::vector<ConstraintRow>& rs) {
    Eigen::VectorXd g(m);
    for (Eigen::Index r = 0; r < m; ++r) g[r] = (rs[static_cast<std::size_t>(r)].value - offset[r]) * inv_scale[r];
    return g;
  };
  const auto done = [&](const Eigen::VectorXd& g) {
    if (homotopy) return g.cwiseAbs().maxCoeff() <= tolerance;
    return out.length_error <= tolerance && out.pin_error <= tolerance;
  };
  Eigen::VectorXd g = scaled(rows);
  out.length_error = p.max_relative_length_error(X);
  out.pin_error = p.max_relative_pin_error(X);
  double mu = 0;  // damping relative to diag(J Jᵀ); 0: Gauss–Newton
  for (; out.iterations < max_iterations && !done(g); ++out.iterations) {
    const SparseMatrix J = inv_scale.asDiagonal() * constraint_jacobian(rows, p.n_points());
    SparseMatrix JJt = J * J.transpose();
    if (mu > 0) {
      const Eigen::VectorXd diag = JJt.diagonal();
      for (Eigen::Index r = 0; r < m; ++r) JJt.coeffRef(r, r) += mu * diag[r];
    }
    const Eigen::SimplicialLDLT<SparseMatrix> ldlt(JJt);
    if (ldlt.info() != Eigen::Success) break;  // dependent rows (a zero-length segment): not reachable this way
    const Eigen::VectorXd dx = J.transpose() * ldlt.solve(g);
    if (!dx.allFinite()) break;
    const MatrixX3 Y = out.points - Eigen::Map<const MatrixX3>(dx.data(), p.n_points(), 3);
    std::vector<ConstraintRow> next = p.rows(Y);
    const Eigen::VectorXd next_g = scaled(next);
    if (!(next_g.squaredNorm() < g.squaredNorm())) {
      mu = mu == 0 ? 1e-4 : 10 * mu;
      if (mu > 1e8) break;  // nothing lowers |g|: rounding, or the linearization is useless here
      continue;
    }
    out.points = Y;
    rows = std::move(next);
    g = next_g;
    mu = mu < 1e-8 ? 0 : 0.1 * mu;
    out.length_error = p.max_relative_length_error(out.points);
    out.pin_error = p.max_relative_pin_error(out.points);
  }
  out.reached = done(g);
  return out;
}

}  // namespace

Retraction retract(const LengthProblem& p, const MatrixX3& X, double tolerance, int max_iterations) {
  return gauss_newton(p, X, Eigen::VectorXd::Zero(p.n_constraint_rows()), tolerance, max_iterations);
}

Retraction restore(const LengthProblem& p, const MatrixX3& X, double tolerance, int max_iterations) {
  Retraction direct = retract(p, X, tolerance, 30);
  if (direct.reached) return direct;
  // Far from the set (a stretched wavy chain: J Jᵀ is a Laplacian and the least-norm correction
  // is dominated by large sideways moves whose second-order terms undo it) Gauss–Newton fails.
  // Newton homotopy: f(X) − (1 − t) f(X₀) = 0 holds at t = 0; t goes to 1 in steps that
  // Gauss–Newton can follow, halved when it cannot (Allgower and Georg, "Numerical
  // continuation methods", 1990, ch. 1).
  std::vector<ConstraintRow> rows0 = p.rows(X);
  Eigen::VectorXd f0(static_cast<Eigen::Index>(rows0.size()));
  for (std::size_t r = 0; r < rows0.size(); ++r) f0[static_cast<Eigen::Index>(r)] = rows0[r].value;
  Retraction out;
  out.points = X;
  double t = 0, dt = 0.25;
  int total = direct.iterations;
  while (t < 1 && total < max_iterations) {
    const double t1 = std::min(1.0, t + dt);
    Retraction step = t1 < 1 ? gauss_newton(p, out.points, (1 - t1) * f0, 1e-6, 20) : retract(p, out.points, tolerance, 50);
    total += step.iterations;
    if (step.reached) {
      out = std::move(step);
      t = t1;
      dt = std::min(2 * dt, 1.0);
    } else {
      dt *= 0.25;
      if (dt < 1e-6) break;
    }
  }
  out.iterations = total;
  out.length_error = p.max_relative_length_error(out.points);
  out.pin_error = p.max_relative_pin_error(out.points);
  out.reached = t >= 1 && out.length_error <= tolerance && out.pin_error <= tolerance;
  return out;
}

double length_rounding_floor(const LengthProblem& p, const MatrixX3& X) {
  const double extent = X.cwiseAbs().maxCoeff();
  const double shortest = p.lengths().lengths().minCoeff();
  return kRoundingSafety * std::numeric_limits<double>::epsilon() * std::max(extent / shortest, 1.0);
}

double attainable_length_tolerance(const LengthProblem& p, const MatrixX3& X, double asked) {
  return std::max(asked, length_rounding_floor(p, X));
}

}  // namespace fairshape
