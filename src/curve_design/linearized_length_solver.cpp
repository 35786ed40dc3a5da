#include "curve_design/linearized_length_solver.h"

#include <cmath>

#include "core/config.h"
#include "core/timer.h"

namespace fairshape {
namespace {

Eigen::Map<const Eigen::VectorXd> flat(const MatrixX3& X) { return {X.data(), X.size()}; }  // 3·point + c

// |∇F(X) + J(X)ᵀλ| / (|QX| + |b|) with the solver's own multipliers: zero at a KKT point.
double stationarity_estimate(const LengthProblem& p, const MatrixX3& X, const Eigen::VectorXd& lambda) {
  const MatrixX3 G = p.objective_gradient(X);
  const SparseMatrix J = constraint_jacobian(p.rows(X), p.n_points());
  const double scale = (p.objective_hessian() * X).norm() + p.objective_linear_term().norm();
  return (flat(G) + J.transpose() * lambda).norm() / std::max(scale, 1e-300);
}

}  // namespace

LengthSolveReport LinearizedLengthSolver::solve(const LengthProblem& p, const MatrixX3& start) const {
  const Timer timer;
  const int n = 3 * p.n_points(), m = p.n_constraint_rows();
  const auto kkt = make_kkt_factor(p, o_.backend, o_.kkt, o_.minres_tolerance);
  LengthSolveReport rep;
  rep.points = start;
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(m);
  const MatrixX3& b = p.objective_linear_term();
  while (rep.solves < o_.tolerances.max_solves) {
    const MatrixX3& X = rep.points;
    const std::vector<ConstraintRow> rows = p.rows(X);
    const bool newton = o_.newton && rep.solves > 0 && rep.length_error < o_.newton_switch;
    if (!kkt->factor(rows, newton ? &lambda : nullptr)) {
      rep.message = "the KKT system could not be factored at solve " + std::to_string(rep.solves + 1) +
                    " (singular: dependent constraints?) " + kkt->last_error();
      return rep;
    }
    // Right-hand side: W X_k − ∇F(X_k) (= b when W = Q) and the linearized rows
    // ∇f_r(X_k)·X = ∇f_r(X_k)·X_k − f_r(X_k).
    Eigen::VectorXd rhs(n + m);
    MatrixX3 rx = b;
    if (newton) {
      Triplets t;
      p.add_constraint_hessians(lambda, t);
      SparseMatrix H(n, n);
      H.setFromTriplets(t.begin(), t.end());
      Eigen::Map<Eigen::VectorXd>(rx.data(), n) += H * flat(X);
    }
    rhs.head(n) = flat(rx);
    for (int r = 0; r < m; ++r) {
      double g_dot_x = 0;
      for (int k = 0; k < rows[r].size; ++k) g_dot_x += rows[r].gradient[k].dot(X.row(rows[r].points[k]).transpose());
      rhs[n + r] = g_dot_x - rows[r].value;
    }
    const Eigen::VectorXd sol = kkt->solve(rhs);
    ++rep.solves;
    rep.outer_iterations = rep.solves;
    if (!sol.allFinite()) {
      rep.message = "solve " + std::to_string(rep.solves) + " produced NaN or infinite values";
      return rep;
    }
    rep.points = Eigen::Map<const MatrixX3>(sol.data(), p.n_points(), 3);
    lambda = sol.tail(m);
    rep.length_error = p.max_relative_length_error(rep.points);
    rep.pin_error = p.max_relative_pin_error(rep.points);
    const double stat = o_.tolerances.stationarity > 0 ? stationarity_estimate(p, rep.points, lambda) : 0.0;
    rep.history.push_back({rep.solves, rep.length_error, stat, timer.seconds()});
    if (rep.length_error <= o_.tolerances.length && rep.pin_error <= o_.tolerances.length &&
        stat <= o_.tolerances.stationarity) {
      rep.converged = true;
      rep.message = "converged after " + std::to_string(rep.solves) + " solve(s)";
      return rep;
    }
  }
  rep.message = "not converged after " + std::to_string(rep.solves) + " solves: max relative length error " +
                format_default(rep.length_error) + " (tolerance " + format_default(o_.tolerances.length) +
                "); raise max_solves, start from a curve nearer the lengths (wrinkle_level), or use newton";
  return rep;
}

}  // namespace fairshape
