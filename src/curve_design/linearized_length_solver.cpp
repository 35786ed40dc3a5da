#include "fairshape/curve_design/linearized_length_solver.h"

#include <algorithm>
#include <cmath>

#include "fairshape/core/config.h"
#include "fairshape/core/timer.h"
#include "fairshape/curve_design/length_manifold.h"
#include "fairshape/curve_design/second_order.h"

namespace fairshape {
namespace {

constexpr int kMaxShifts = 8;  // Newton's curvature shift goes up to 1e3 × Q's largest diagonal entry


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
  // Not a descent direction for φ (a Newton step on indefinite curvature): no step length
  // helps; the caller takes a step of the paper's system instead.
  if (slope >= 0) return -1;
  double alpha = 1;
  for (int k = 0; k < 40; ++k, alpha *= 0.5) {
    out = X + alpha * step;
    const double phi = p.objective(out) + nu * l1_violation(p.rows(out));
    // The slack: near convergence the decrease drowns in the rounding of a sum of n terms.
    if (phi <= reference + 1e-4 * alpha * slope + 1e-13 * std::abs(reference)) return alpha;
  }
  out = full;  // no decrease within 40 halvings (rounding): the paper's full step
  return 1;
}

// Leaves a constrained saddle along its negative-curvature direction d (unit norm): a move of
// about a tenth of a mean segment per point, downhill to first order (the sign of ∇F·d) — the
// paper's steps then bring the lengths back, and the second-order decrease ½α²dᵀWd < 0 makes the
// next stationary point a lower one.
MatrixX3 escape_saddle(const LengthProblem& p, const MatrixX3& X, const MatrixX3& d) {
  const Eigen::VectorXd& lengths = p.reference_lengths();
  const double mean = lengths.size() ? lengths.mean() : 1.0;
  const double alpha = 0.1 * mean * std::sqrt(static_cast<double>(p.n_points()));
  const double sign = (p.objective_gradient(X).array() * d.array()).sum() > 0 ? -1.0 : 1.0;
  return X + sign * alpha * d;
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
  const double q_scale = std::max(p.objective_hessian().diagonal().cwiseAbs().maxCoeff(), 1e-300);
  const MatrixX3& b = p.objective_linear_term();
  // The tolerance asked, or the rounding floor of this curve when that is larger (a relative
  // length error below n·ε cannot be certified: the default 1e-10 at 131k points).
  const double tol = attainable_length_tolerance(p, start, o_.tolerances.length);
  const std::string tol_note =
      tol > o_.tolerances.length ? " (length tolerance raised to the rounding floor " + format_default(tol) + ")" : "";
  // Stall detection: the distance to the tolerances, max(length error / tol, stationarity /
  // its tolerance), must fall by a tenth within stall_window solves (the paper's loop
  // converges linearly but not monotonically — at β = 0.5 on Figure 1 it creeps for hundreds
  // of solves — so the window is long; a loop that cycles is caught instead of burning
  // max_solves).
  double window_start = INFINITY, best_progress = INFINITY;
  int window_solves = 0;
  while (rep.solves < o_.tolerances.max_solves) {
    const MatrixX3& X = rep.points;
    const std::vector<ConstraintRow> rows = p.rows(X);
    const bool newton = o_.newton && rep.solves > 0 && rep.length_error < o_.newton_switch;
    // One linearized step: W = Q (the paper), or Newton's W = Q + Σλ∇²f + δI, δ raised from 0
    // until the KKT inertia is right (optimized back end) and the step descends on the ℓ1
    // merit (an indefinite W on the tangent space of the lengths gives steps towards saddles);
    // past kMaxShifts, the paper's step.
    const Eigen::VectorXd previous_lambda = lambda;
    double shift = 0;
    MatrixX3 next;
    for (int attempt = 0;; ++attempt) {
      const bool use_newton = newton && attempt <= kMaxShifts;
      if (!kkt->factor(X, rows, use_newton ? &previous_lambda : nullptr, use_newton ? shift : 0.0)) {
        rep.summary.message = "the KKT system could not be factored at solve " + std::to_string(rep.solves + 1) +
                              " (singular: dependent constraints?) " + kkt->last_error();
        return rep;
      }
      // Inertia control (where the LDLᵀ gives it): W + δI must be positive definite on the
      // tangent space — exactly m negative pivots — or the step heads for a saddle; raising δ
      // before solving saves a solve and a line search per refused shift.
      if (use_newton && kkt->negative_pivots() > m) {
        shift = shift == 0 ? 1e-4 * q_scale : 10 * shift;
        continue;
      }
      // Right-hand side: W X_k − ∇F(X_k) (= b when W = Q) and the linearized rows
      // ∇f_r(X_k)·X = ∇f_r(X_k)·X_k − f_r(X_k).
      Eigen::VectorXd rhs(n + m);
      MatrixX3 rx = b;
      if (use_newton) {
        Triplets t;
        p.add_constraint_hessians(previous_lambda, X, t);
        SparseMatrix H(n, n);
        H.setFromTriplets(t.begin(), t.end());
        Eigen::Map<Eigen::VectorXd>(rx.data(), n) += H * flat(X) + shift * flat(X);
      }
      rhs.head(n) = flat(rx);
      for (int r = 0; r < m; ++r) {
        double g_dot_x = 0;
        for (int k = 0; k < rows[r].size; ++k) g_dot_x += rows[r].grad(k).dot(X.row(rows[r].point(k)).transpose());
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
      if (!o_.line_search) {
        next = full;
        break;
      }
      if (merit_step(p, X, rows, full, merit, lambda, next) >= 0) break;
      if (!use_newton) {
        next = full;  // the paper's own system (W = Q): its full step, as published
        break;
      }
      shift = shift == 0 ? 1e-4 * q_scale : 10 * shift;
    }
    rep.points = std::move(next);
    rep.length_error = p.max_relative_length_error(rep.points);
    rep.summary.residual = rep.length_error;
    rep.pin_error = p.max_relative_pin_error(rep.points);
    const double stat = o_.tolerances.stationarity > 0 ? stationarity_estimate(p, rep.points, lambda) : 0.0;
    rep.history.push_back({rep.solves, rep.length_error, stat, timer.seconds(), p.objective(rep.points)});
    if (rep.length_error <= tol && rep.pin_error <= tol && stat <= o_.tolerances.stationarity) {
      rep.summary.termination = Termination::Converged;
      rep.summary.message = "converged after " + std::to_string(rep.solves) + " solve(s)" + tol_note;
      // Stationary is not yet minimal: at a saddle, step off it along negative curvature and go
      // on; after o_.saddle_escapes the saddle is reported (not_a_minimum).
      const bool may_escape = o_.tolerances.stationarity > 0 && rep.saddle_escapes < o_.saddle_escapes;
      const SecondOrderMode mode = o_.tolerances.second_order;
      const SecondOrderCheck so = may_escape ? second_order_check(p, rep.points, mode, true) : SecondOrderCheck{};
      if (so.checked && !so.is_minimum(kSecondOrderTolerance) && so.direction.rows() == p.n_points()) {
        ++rep.saddle_escapes;
        window_start = best_progress = INFINITY;  // a new descent: the stall window restarts
        rep.points = escape_saddle(p, rep.points, so.direction);
        rep.length_error = p.max_relative_length_error(rep.points);
        merit = MeritHistory{};
        continue;
      }
      judge_second_order(p, rep, o_.tolerances.stationarity > 0, mode, may_escape ? &so : nullptr);
      if (rep.saddle_escapes > 0) rep.summary.message += " (" + std::to_string(rep.saddle_escapes) + " saddle(s) left on the way)";
      return rep;
    }
    const double progress = std::max({rep.length_error / tol, rep.pin_error / tol,
                                      o_.tolerances.stationarity > 0 ? stat / o_.tolerances.stationarity : 0.0});
    best_progress = std::min(best_progress, progress);
    if (best_progress <= 0.9 * window_start) {
      window_start = best_progress;
      window_solves = 0;
    } else if (++window_solves >= o_.stall_window) {
      rep.summary.termination = Termination::Stalled;
      rep.summary.message = "stalled: the distance to the tolerances did not fall by a tenth over " + std::to_string(o_.stall_window) +
                            " solves (after " + std::to_string(rep.solves) + "): max relative length error " +
                            format_default(rep.length_error) + " (tolerance " + format_default(tol) + "), stationarity " +
                            format_default(stat) + "; try the globalized solver (type: trust_region)";
      return rep;
    }
  }
  rep.summary.termination = Termination::MaxIterations;
  rep.summary.message = "not converged after " + std::to_string(rep.solves) + " solves: max relative length error " +
                format_default(rep.length_error) + " (tolerance " + format_default(tol) +
                "); raise max_solves, start from a curve nearer the lengths (wrinkle_level), or use newton";
  return rep;
}

}  // namespace fairshape
