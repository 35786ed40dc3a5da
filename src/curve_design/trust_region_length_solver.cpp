#include "fairshape/curve_design/trust_region_length_solver.h"

#include <algorithm>
#include <cmath>

#include "fairshape/core/config.h"
#include "fairshape/core/message_format.h"
#include "fairshape/core/timer.h"
#include "fairshape/curve_design/length_manifold.h"
#include "fairshape/curve_design/reduced_eigenvalue.h"
#include "fairshape/curve_design/second_order.h"
#include "fairshape/curve_design/subspace_step.h"

namespace fairshape {
namespace {

Eigen::Map<const Eigen::VectorXd> flat(const MatrixX3& X) { return {X.data(), X.size()}; }  // 3·point + c

// Nocedal & Wright, Algorithm 4.1: accept when ρ ≥ η; shrink below ¼, grow above ¾.
constexpr double kAccept = 0.1, kShrink = 0.25, kGrow = 0.75;
// Inertia control without a dense eigenvalue: the shift grows by this factor from this
// fraction of Q's largest diagonal entry, at most kMaxShiftTries times per iteration.
constexpr double kShiftGrowth = 10, kFirstShift = 1e-6;
constexpr int kMaxShiftTries = 12;
constexpr double kDefaultStationarity = 1e-8;
constexpr int kInverseIterations = 20;

// Gauss–Newton corrections δ minimizing ½ δᵀ(Q + εI)δ subject to J δ = −f: the least-*bending*
// correction (the normal step of Byrd and Omojokun's composite-step SQP, in the objective's
// metric). Far from the lengths the Euclidean least-norm correction of a stretched wavy chain
// is dominated by large sideways moves whose second-order terms undo it; in the bending metric
// the correction is smooth (an affine compression costs no bending) and Gauss–Newton converges.
// Each correction is halved until the scaled residual |f / l²| decreases.
Retraction restore_in_objective_metric(const LengthProblem& p, KktFactor& kkt, const MatrixX3& X, double tolerance,
                                       int& solves) {
  const int N = p.n_points(), n = 3 * N, m = p.n_constraint_rows();
  const double eps = 1e-8 * std::max(p.objective_hessian().diagonal().cwiseAbs().maxCoeff(), 1e-300);
  const auto scaled_norm = [&](const std::vector<ConstraintRow>& rows) {
    double s = 0;
    for (int r = 0; r < m; ++r) s += std::pow(rows[r].value / p.row_scale(r), 2);
    return s;
  };
  Retraction out;
  out.points = X;
  std::vector<ConstraintRow> rows = p.rows(X);
  double residual = scaled_norm(rows);
  for (; out.iterations < 100; ++out.iterations) {
    out.length_error = p.max_relative_length_error(out.points);
    out.pin_error = p.max_relative_pin_error(out.points);
    if (out.length_error <= tolerance && out.pin_error <= tolerance) break;
    if (!kkt.factor(out.points, rows, nullptr, eps)) break;
    ++solves;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + m);
    for (int r = 0; r < m; ++r) rhs[n + r] = -rows[r].value;
    const Eigen::VectorXd delta = kkt.solve(rhs).head(n);
    if (!delta.allFinite()) break;
    bool lowered = false;
    double alpha = 1;
    for (int k = 0; k < 30 && !lowered; ++k, alpha *= 0.5) {
      const MatrixX3 Y = out.points + alpha * Eigen::Map<const MatrixX3>(delta.data(), N, 3);
      std::vector<ConstraintRow> next = p.rows(Y);
      const double next_residual = scaled_norm(next);
      if (next_residual < residual) {
        out.points = Y;
        rows = std::move(next);
        residual = next_residual;
        lowered = true;
      }
    }
    if (!lowered) break;  // rounding, or no decrease along the correction
  }
  out.reached = out.length_error <= tolerance && out.pin_error <= tolerance;
  return out;
}

}  // namespace

LengthSolveReport TrustRegionLengthSolver::solve(const LengthProblem& p, const MatrixX3& start) const {
  const Timer timer;
  const int N = p.n_points(), n = 3 * N, m = p.n_constraint_rows();
  LengthSolveReport rep;
  rep.points = start;
  const double tol = attainable_length_tolerance(p, start, o_.tolerances.length);
  // Every iterate holds the lengths, so "lengths alone" (stationarity 0) would stop at once:
  // this solver always asks for stationarity, by default 1e-8.
  const double stat_tol = o_.tolerances.stationarity > 0 ? o_.tolerances.stationarity : kDefaultStationarity;
  const std::string tol_note = tol > o_.tolerances.length ? " (length tolerance raised to the rounding floor " +
                                                                format_default(tol) + ")"
                                                          : "";
  // The retraction aims below the tolerance so that accepted points never limit convergence;
  // it stops at its own rounding floor if that is higher.
  const double retract_tol = 0.1 * tol;

  // 1. Onto the lengths: Gauss–Newton in the objective's metric, then (when that stops short)
  // the Euclidean homotopy of length_manifold.h.
  const auto kkt = make_kkt_factor(p, o_.backend, o_.kkt, 1e-13);
  Retraction r0 = restore_in_objective_metric(p, *kkt, start, retract_tol, rep.solves);
  if (!(r0.length_error <= tol && r0.pin_error <= tol)) r0 = restore(p, r0.points, retract_tol);
  rep.points = r0.points;
  rep.length_error = r0.length_error;
  rep.pin_error = r0.pin_error;
  rep.summary.residual = rep.length_error;
  if (!(r0.length_error <= tol && r0.pin_error <= tol)) {
    rep.summary.termination = Termination::Infeasible;
    rep.summary.message = "Gauss-Newton and a homotopy from the start reached a max relative length error of " +
                          format_default(r0.length_error) + " (pins " + format_default(r0.pin_error) + ") in " +
                          std::to_string(r0.iterations) + " corrections, tolerance " + format_default(tol) +
                          ": no curve of the reference lengths near the start (check pins and lengths)";
    return rep;
  }

  const Eigen::VectorXd& lengths = p.reference_lengths();
  // Radii in units of the curve: a copy ×1000 takes the same steps.
  double radius = o_.initial_radius * lengths.mean() * std::sqrt(static_cast<double>(N));
  const double max_radius = lengths.sum(), min_radius = 1e-15 * std::max(rep.points.cwiseAbs().maxCoeff(), lengths.mean());
  const double q_scale = std::max(p.objective_hessian().diagonal().cwiseAbs().maxCoeff(), 1e-300);
  // The dense reduced Hessian (an O(n³) eigen-solve per iteration) only when second_order: dense
  // asks for it; otherwise inertia and inverse iteration on the banded factor at every size.
  const SecondOrderMode mode = o_.tolerances.second_order;
  const bool dense = mode == SecondOrderMode::Dense && N <= o_.dense_limit;
  MatrixX3 X = rep.points;
  double F = p.objective(X);
  double best_F = F, best_stat = INFINITY, last_min_eig = std::nan("");
  // solves: KKT systems solved (restoration and steps); inertia checks are factorizations
  // without a solve, counted apart (the message gives them).
  int since_progress = 0, iterations = 0, inertia_checks = 0;
  Eigen::MatrixXd block;  // the block of soft modes, kept between iterations (block_size > 1)
  double last_sigma = 0;  // the block path's last shift with the right inertia
  // The progress window (5a): F, stationarity and negative count where it started.
  double window_F = F, window_stat = INFINITY;
  int window_negative = -1, window_start = 0;

  const auto finish = [&](Termination t, const std::string& why) {
    rep.points = X;
    rep.summary.termination = t;
    rep.summary.iterations = rep.solves;
    rep.outer_iterations = iterations;
    rep.summary.message = why + " [" + std::to_string(inertia_checks) + " inertia checks]" + tol_note;
    return rep;
  };

  while (rep.solves < o_.tolerances.max_solves) {
    const std::vector<ConstraintRow> rows = p.rows(X);
    const Eigen::VectorXd lambda = least_squares_multipliers(p, X);
    // This iterate, and its smallest-eigenvalue estimate when one is made (the progress stop
    // returns it, so that the count and the estimate it reports are the returned curve's).
    const MatrixX3 X_iterate = X;
    double iterate_min_eig = std::nan("");
    if (!lambda.allFinite()) return finish(Termination::NumericalFailure, "the constraint rows are dependent at iteration " +
                                                                           std::to_string(iterations) + " (a zero-length segment?)");
    const SparseMatrix J = constraint_jacobian(rows, N);
    const MatrixX3 G = p.objective_gradient(X);
    const Eigen::VectorXd g = flat(G);
    const double stat_scale = std::max((p.objective_hessian() * X).norm() + p.objective_linear_term().norm(), 1e-300);
    const double stat = (g + J.transpose() * lambda).norm() / stat_scale;
    rep.length_error = p.max_relative_length_error(X);
    rep.pin_error = p.max_relative_pin_error(X);
    rep.summary.residual = rep.length_error;
    rep.history.push_back({rep.solves, rep.length_error, stat, timer.seconds(), p.objective(X)});

    // Curvature on the tangent space (same least-squares λ as the step's W): the LDLᵀ inertia
    // first (one banded factorization, second_order.h), the dense eigenpair only where that
    // finds negative curvature (for σ and the direction) or to report the answer's eigenvalue.
    const bool first_order = rep.length_error <= tol && rep.pin_error <= tol && stat <= stat_tol;
    // One factorization at the check's shift serves twice: its inertia is the second-order
    // test, and its solve is the step whenever no larger shift is needed (1e-8 of Q's scale
    // leaves Newton's convergence intact to that level). Back ends without inertia (SparseLU)
    // ask the shared banded check, so both back ends decide alike.
    const double base_shift = kSecondOrderTolerance * q_scale;
    if (!kkt->factor(X, rows, &lambda, base_shift))
      return finish(Termination::NumericalFailure, "the KKT system could not be factored at solve " +
                                                       std::to_string(rep.solves + 1) + " " + kkt->last_error());
    const auto negative_count = [&](double shift) {
      const int pivots = kkt->negative_pivots();
      return pivots >= 0 ? std::max(pivots - m, 0) : reduced_hessian_negative_count(p, X, shift);
    };
    const int inertia = negative_count(base_shift);
    ++inertia_checks;
    bool negative = inertia > 0;
    SecondOrderCheck so;
    // At a candidate answer the dense check (up to its limit) also gives the eigenvalue reported.
    if ((dense && negative) || (first_order && mode == SecondOrderMode::Dense && N <= kSecondOrderDenseLimit)) {
      so = check_second_order(p, X);
      if (so.checked) {
        negative = so.min_eigenvalue < -kSecondOrderTolerance * so.max_abs_eigenvalue;
        last_min_eig = iterate_min_eig = so.min_eigenvalue;
      }
    }
    // At the answer without the dense check: the eigenvalue reported is bracketed by inertia
    // bisection on the banded factor (reduced_eigenvalue.h), O(n), the verdict staying the
    // inertia's above.
    ReducedEigenvalueBracket bracket;
    if (first_order && !negative && !so.checked && mode == SecondOrderMode::Inertia) bracket = smallest_reduced_eigenvalue(p, X);
    bool have_direction = negative && so.checked;

    if (first_order && !negative) {
      rep.points = X;
      std::string how;
      if (so.checked) {
        rep.min_reduced_hessian_eig = so.min_eigenvalue;
        how = "reduced Hessian's smallest eigenvalue " + sci(so.min_eigenvalue);
      } else if (inertia < 0) {
        how = "second order not checked (the inertia check failed)";
      } else if (bracket.ok) {
        rep.min_reduced_hessian_eig = bracket.estimate();
        how = "reduced Hessian positive semidefinite by LDLT inertia, smallest eigenvalue in [" + sci(bracket.lower) + ", " +
              sci(bracket.upper) + "] (inertia bisection)";
      } else {
        how = std::string("reduced Hessian positive semidefinite by LDLT inertia (smallest eigenvalue ") +
              (mode == SecondOrderMode::Off ? "not estimated: second_order off)" : "not estimated: the bisection failed)");
      }
      return finish(Termination::Converged, "converged after " + std::to_string(rep.solves) + " solve(s), " +
                                                std::to_string(iterations) + " trust-region iteration(s): " + how +
                                                (rep.saddle_escapes ? ", " + std::to_string(rep.saddle_escapes) + " negative-curvature step(s)" : ""));
    }

    // 2. The shifted Newton step: σ = 2|λ_min| from the dense eigenvalue, or (above the dense
    // limit) raised until the inertia is right — the same check for both back ends.
    double sigma = have_direction ? 2 * -so.min_eigenvalue : base_shift;
    if (have_direction && !kkt->factor(X, rows, &lambda, sigma))
      return finish(Termination::NumericalFailure, "the shifted KKT system could not be factored at solve " + std::to_string(rep.solves + 1));
    const bool use_block = negative && !have_direction && o_.block_size > 1;
    if (use_block) {
      // Bracket the smallest power-of-ten multiple of the previous shift with the right
      // inertia, from a tenth of it: the soft modes change little between iterations, so two
      // or three factorizations instead of climbing from kFirstShift every time.
      const double floor = kFirstShift * q_scale;
      double trial = std::max(floor, (last_sigma > 0 ? last_sigma : floor) / kShiftGrowth), good = 0;
      for (int attempt = 0;; ++attempt) {
        if (!kkt->factor(X, rows, &lambda, trial))
          return finish(Termination::NumericalFailure, "the shifted KKT system could not be factored at solve " + std::to_string(rep.solves + 1));
        const int left = negative_count(trial);
        ++inertia_checks;
        if (left < 0 || attempt >= 2 * kMaxShiftTries)
          return finish(Termination::NumericalFailure, "no shift up to " + sci(trial) +
                                                           " made the reduced Hessian positive definite at iteration " +
                                                           std::to_string(iterations));
        if (left == 0) {
          good = trial;
          if (trial / kShiftGrowth < floor) break;
          trial /= kShiftGrowth;  // still right: try lower
        } else if (good > 0) {
          trial = good;  // the last right one: factor it again
          if (!kkt->factor(X, rows, &lambda, trial))
            return finish(Termination::NumericalFailure, "the shifted KKT system could not be factored at solve " + std::to_string(rep.solves + 1));
          break;
        } else {
          trial *= kShiftGrowth;
        }
      }
      sigma = last_sigma = good;
    } else if (negative && !have_direction) {
      sigma = kFirstShift * q_scale;
      for (int attempt = 0;; ++attempt, sigma *= kShiftGrowth) {
        if (!kkt->factor(X, rows, &lambda, sigma))
          return finish(Termination::NumericalFailure, "the shifted KKT system could not be factored at solve " + std::to_string(rep.solves + 1));
        const int left = negative_count(sigma);
        ++inertia_checks;
        if (left == 0) break;
        if (left < 0 || attempt >= kMaxShiftTries)
          return finish(Termination::NumericalFailure, "no shift up to " + sci(sigma) +
                                                           " made the reduced Hessian positive definite at iteration " +
                                                           std::to_string(iterations));
      }
    }
    const SparseMatrix W = lagrangian_hessian(p, X, lambda);
    RitzPairs ritz;
    if (use_block) {
      // Above the dense limit, block_size > 1: the k softest modes by block inverse iteration
      // on the factor just made, warm-started from the previous iteration's block
      // (subspace_step.h); the step is then the exact trust-region step in span{s_N, block}.
      if (block.rows() != n || block.cols() == 0) block = initial_block(n, o_.block_size);
      ritz = block_inverse_iteration(*kkt, W, block, m, o_.block_steps);
      rep.solves += ritz.solves;
      if (ritz.values.size() > 0) last_min_eig = iterate_min_eig = ritz.values[0];
      if (block.cols() < o_.block_size) {  // refill lost columns so the block keeps its width
        const Eigen::MatrixXd fresh = initial_block(n, o_.block_size);
        Eigen::MatrixXd wider(n, o_.block_size);
        wider << block, fresh.rightCols(o_.block_size - block.cols());
        block = wider;
      }
    } else if (negative && !have_direction) {
      // Above the dense limit: the direction by inverse iteration on the tangent space with the
      // factor just made, W + σI = W − μI with μ = −σ ≤ λ_min (σ is the first shift with the
      // right inertia), each iteration one solve [W + σI, Jᵀ; J, 0][w; ·] = [v; 0], so w =
      // Z (Zᵀ(W + σI)Z)⁻¹ Zᵀ v converges to λ_min's eigenvector (Golub & Van Loan §8.2.2);
      // its Rayleigh quotient estimates λ_min.
      Eigen::VectorXd v(n), rhs_v = Eigen::VectorXd::Zero(n + m);
      for (int i = 0; i < n; ++i) v[i] = std::sin(1.7 * i + 0.3) + 0.5 * std::cos(0.37 * i);  // deterministic start
      for (int k = 0; k < kInverseIterations; ++k) {
        rhs_v.head(n) = v / v.norm();
        v = kkt->solve(rhs_v).head(n);
        ++rep.solves;
        if (!v.allFinite() || v.norm() == 0) break;
      }
      if (v.allFinite() && v.norm() > 0) {
        v /= v.norm();
        const double rayleigh = v.dot(W * v);
        if (rayleigh < 0) {
          so.checked = true;
          so.min_eigenvalue = rayleigh;
          so.direction = Eigen::Map<const MatrixX3>(v.data(), N, 3);
          last_min_eig = iterate_min_eig = rayleigh;
          have_direction = true;
        }
      }
    }
    Eigen::VectorXd rhs(n + m);
    rhs.head(n) = -g;
    for (int r = 0; r < m; ++r) rhs[n + r] = -rows[r].value;  // also removes the retraction's residual
    ++rep.solves;
    Eigen::VectorXd s = kkt->solve(rhs).head(n);
    if (!s.allFinite()) return finish(Termination::NumericalFailure, "solve " + std::to_string(rep.solves) + " produced NaN or infinite values");
    ++iterations;

    // 3. Into the radius; at negative curvature, the eigenvector fills what is left of it (or,
    // with a block, the exact step in span{s, Ritz vectors}).
    bool escape = false;
    double predicted = 0;
    if (use_block && ritz.vectors.cols() > 0) {
      Eigen::MatrixXd basis(n, 1 + ritz.vectors.cols());
      basis << s, ritz.vectors;
      const SubspaceStep sub = subspace_trust_region_step(basis, W, g, radius);
      s = sub.s;
      predicted = sub.predicted;
      escape = sub.negative_curvature;
    } else if (s.norm() > radius) {
      s *= radius / s.norm();
    } else if (have_direction) {
      // Downhill to first order; where ∇F·d is rounding (a planar curve's out-of-plane mode,
      // which leaves the plane to either side at the same cost) the sign is fixed by d's
      // largest entry, so both back ends and every run take the same side.
      Eigen::VectorXd d = flat(so.direction);
      Eigen::Index largest = 0;
      d.cwiseAbs().maxCoeff(&largest);
      const double slope = g.dot(d);
      if (std::abs(slope) > 1e-10 * g.norm() ? slope > 0 : d[largest] < 0) d = -d;
      const double tau = std::sqrt(std::max(radius * radius - s.squaredNorm(), 0.0));
      s += tau * d;
      escape = tau > 0;
    }
    if (!(use_block && ritz.vectors.cols() > 0)) predicted = -(g.dot(s) + 0.5 * s.dot(W * s));

    // 4. Retract and compare the decrease with the model's.
    const MatrixX3 trial = X + Eigen::Map<const MatrixX3>(s.data(), N, 3);
    const Retraction back = retract(p, trial, retract_tol, 30);
    double rho = -1, trial_F = INFINITY;
    if (back.length_error <= tol && back.pin_error <= tol) {
      trial_F = p.objective(back.points);
      const double actual = F - trial_F;
      // Rounding: decreases below a few ulps of F are noise in both numbers.
      const double noise = 1e-14 * std::abs(F);
      rho = predicted > noise ? actual / predicted : (actual >= -noise ? 1.0 : -1.0);
    }
    const double step = s.norm();
    if (rho >= kAccept) {
      X = back.points;
      F = trial_F;
      if (escape) ++rep.saddle_escapes;
    }
    if (rho < kShrink) radius = kShrink * std::min(radius, step);
    else if (rho > kGrow && step >= 0.9 * radius) radius = std::min(2 * radius, max_radius);

    // 5a. Slow progress with negative curvature left (the glassy tail of a curve with many soft
    // modes: Figure 1's edit from 8k points up): F down by a fraction progress_decrease, the
    // stationarity by a tenth or the negative count by half within progress_window iterations,
    // else stop and say so rather than spend the budget (papers/sauvage/README.md, *Solvers*).
    if (o_.progress_window > 0) {
      if (inertia <= 0 || F < window_F - o_.progress_decrease * std::abs(window_F) || stat < 0.1 * window_stat ||
          2 * inertia <= window_negative) {
        window_F = F;
        window_stat = stat;
        window_negative = inertia;
        window_start = iterations;
      } else if (iterations - window_start >= o_.progress_window) {
        X = X_iterate;  // the curve the count and the estimate below were measured on
        rep.min_reduced_hessian_eig = iterate_min_eig;
        return finish(Termination::Stalled,
                      "stalled with negative curvature left: the reduced Hessian has " + std::to_string(inertia) +
                          " negative eigenvalue(s) (LDLT inertia; " +
                          (iterate_min_eig < 0 ? "the smallest ≤ " + sci(iterate_min_eig) + ", a Rayleigh quotient" : std::string("the smallest not estimated")) +
                          "), and over the last " +
                          std::to_string(iterations - window_start) + " iterations F fell by less than " +
                          format_default(100 * o_.progress_decrease) + " %, the stationarity by less than a tenth and the negative count by less than half (trust_region.progress_window, progress_decrease) after " +
                          std::to_string(rep.solves) + " solves; max relative length error " + format_default(rep.length_error) +
                          ", stationarity " + sci(stat) + " (tolerance " + sci(stat_tol) + ")");
      }
    }
    // 5b. Progress: F down by more than rounding, or the stationarity down by a tenth.
    if (F < best_F - 1e-13 * std::abs(best_F) || stat < 0.1 * best_stat) {
      since_progress = 0;
      best_F = std::min(best_F, F);
      best_stat = std::min(best_stat, stat);
    } else if (++since_progress >= o_.stall_window || radius < min_radius) {
      const std::string where = "max relative length error " + format_default(rep.length_error) + ", stationarity " +
                                sci(stat) + " (tolerance " + sci(stat_tol) + ")";
      if (negative) {
        if (so.checked) rep.min_reduced_hessian_eig = so.min_eigenvalue;
        return finish(Termination::NotAMinimum, "not a minimum: no step along the negative curvature (reduced Hessian's smallest eigenvalue " +
                                                    (so.checked ? sci(so.min_eigenvalue) : "not estimated, LDLT inertia") +
                                                    ") decreased F within " + std::to_string(since_progress) + " iterations; " + where);
      }
      return finish(Termination::Stalled, std::string("stalled: ") +
                                              (radius < min_radius ? "the trust region shrank to rounding"
                                                                   : "no decrease of F over " + std::to_string(o_.stall_window) + " iterations") +
                                              " after " + std::to_string(rep.solves) + " solves; " + where);
    }
  }
  rep.min_reduced_hessian_eig = last_min_eig;
  return finish(Termination::MaxIterations,
                "not converged after " + std::to_string(rep.solves) + " solves (" + std::to_string(iterations) +
                    " trust-region iterations): max relative length error " + format_default(rep.length_error));
}

}  // namespace fairshape
