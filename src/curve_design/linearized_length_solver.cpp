#include "curve_design/linearized_length_solver.h"

#include <algorithm>
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

double l1_violation(const std::vector<ConstraintRow>& rows) {
  double s = 0;
  for (const auto& r : rows) s += std::abs(r.value);
  return s;
}

// Backtracks from the full step X → X̂ until the ℓ1 merit φ = F + ν Σ|f_r| falls below the
// largest of its last few values by the Armijo fraction of its directional derivative
// (non-monotone, Grippo–Lampariello–Lucidi: full steps are kept whenever they do not undo
// recent progress, which a monotone search would refuse near the solution). With W positive
// definite and ν above every |λ̂_r| the step is a descent direction.
struct MeritHistory {
  double nu = 0;               // never decreased
  std::vector<double> recent;  // merit values of the last iterates (at the current ν)
};

double merit_step(const LengthProblem& p, const MatrixX3& X, const std::vector<ConstraintRow>& rows, const MatrixX3& full,
                  MeritHistory& h, const Eigen::VectorXd& lambda, MatrixX3& out) {
  const double nu = std::max(h.nu, 1.1 * lambda.cwiseAbs().maxCoeff());
  if (nu != h.nu) h.recent.clear();  // values at another ν are not comparable
  h.nu = nu;
  const MatrixX3 step = full - X;
  const double c0 = l1_violation(rows), phi0 = p.objective(X) + nu * c0;
  h.recent.push_back(phi0);
  if (h.recent.size() > 5) h.recent.erase(h.recent.begin());
  const double reference = *std::max_element(h.recent.begin(), h.recent.end());
  const double slope = (p.objective_gradient(X).array() * step.array()).sum() - nu * c0;
  double alpha = 1;
  for (int k = 0; k < 40; ++k, alpha *= 0.5) {
    out = X + alpha * step;
    const double phi = p.objective(out) + nu * l1_violation(p.rows(out));
    // The slack: near convergence the decrease drowns in the rounding of a sum of n terms.
    if (slope >= 0 || phi <= reference + 1e-4 * alpha * slope + 1e-13 * std::abs(reference)) return alpha;
  }
  out = full;  // no decrease found (not a descent direction): take the paper's full step
  return 1;
}

}  // namespace

LengthSolveReport LinearizedLengthSolver::solve(const LengthProblem& p, const MatrixX3& start) const {
  const Timer timer;
  const int n = 3 * p.n_points(), m = p.n_constraint_rows();
  const auto kkt = make_kkt_factor(p, o_.backend, o_.kkt, o_.minres_tolerance);
  LengthSolveReport rep;
  rep.points = start;
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(m);
  MeritHistory merit;
  const MatrixX3& b = p.objective_linear_term();
  while (rep.solves < o_.tolerances.max_solves) {
    const MatrixX3& X = rep.points;
    const std::vector<ConstraintRow> rows = p.rows(X);
    const bool newton = o_.newton && rep.solves > 0 && rep.length_error < o_.newton_switch;
    if (!kkt->factor(rows, newton ? &lambda : nullptr)) {
      rep.summary.message = "the KKT system could not be factored at solve " + std::to_string(rep.solves + 1) +
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
    rep.summary.iterations = rep.solves;
    rep.outer_iterations = rep.solves;
    if (!sol.allFinite()) {
      rep.summary.message = "solve " + std::to_string(rep.solves) + " produced NaN or infinite values";
      return rep;
    }
    const MatrixX3 full = Eigen::Map<const MatrixX3>(sol.data(), p.n_points(), 3);
    lambda = sol.tail(m);
    if (o_.line_search) {
      MatrixX3 next;
      merit_step(p, X, rows, full, merit, lambda, next);
      rep.points = std::move(next);
    } else {
      rep.points = full;
    }
    rep.length_error = p.max_relative_length_error(rep.points);
    rep.summary.residual = rep.length_error;
    rep.pin_error = p.max_relative_pin_error(rep.points);
    const double stat = o_.tolerances.stationarity > 0 ? stationarity_estimate(p, rep.points, lambda) : 0.0;
    rep.history.push_back({rep.solves, rep.length_error, stat, timer.seconds()});
    if (rep.length_error <= o_.tolerances.length && rep.pin_error <= o_.tolerances.length &&
        stat <= o_.tolerances.stationarity) {
      rep.summary.termination = Termination::Converged;
      rep.summary.message = "converged after " + std::to_string(rep.solves) + " solve(s)";
      return rep;
    }
  }
  rep.summary.termination = Termination::MaxIterations;
  rep.summary.message = "not converged after " + std::to_string(rep.solves) + " solves: max relative length error " +
                format_default(rep.length_error) + " (tolerance " + format_default(o_.tolerances.length) +
                "); raise max_solves, start from a curve nearer the lengths (wrinkle_level), or use newton";
  return rep;
}

}  // namespace fairshape
