#include "fairshape/solver/iterative.h"

#include "fairshape/core/backend.h"
#if FAIRSHAPE_WITH_TBB  // both back ends' monitors: serial without TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

namespace fairshape {

IterativeOptions IterativeOptions::from_config(Config& cfg) {
  IterativeOptions o;
  o.tolerance = cfg.get_number("tolerance", o.tolerance, 0.0, 1.0, "relative residual to stop at (0: off)");
  o.energy_tolerance = cfg.get_number("energy_tolerance", o.energy_tolerance, 0.0, 1.0,
                                      "stop when a check's energy decrease is at most this fraction of the "
                                      "decrease since the start (0: off)");
  o.error_tolerance = cfg.get_number("error_tolerance", o.error_tolerance, 0.0, 1.0,
                                     "stop when the estimated relative error is at most this (0: off; CG: A-norm, "
                                     "Hestenes-Stiefel; stationary solvers: the steps' geometric tail)");
  o.error_delay = cfg.get_int("error_delay", o.error_delay, 1, 1000,
                              "CG iterations between an iterate and its error estimate (longer: tighter)");
  // Stopping on the error replaces the default residual rule; a residual tolerance given as
  // well must hold too.
  if (o.error_tolerance > 0 && !cfg.has("tolerance")) o.tolerance = 0;
  o.max_iterations = cfg.get_int("max_iterations", o.max_iterations, 1, 100000000, "iteration cap");
  o.check_every = cfg.get_int("check_every", o.check_every, 1, 1000000, "sweeps between residual checks");
  return o;
}

double sor_omega_from_config(Config& cfg) {
  Config sub = cfg.child("sor", "options of the sor solver");
  const double omega = sub.get<double>("omega", 1.5, "relaxation factor, in the open interval (0, 2)");
  if (!(omega > 0.0 && omega < 2.0))
    throw InvalidConfig(sub.key_path("omega") + ": " + std::to_string(omega) +
                        " is outside (0, 2), where SOR diverges");
  sub.check_no_unknown_keys();
  return omega;
}

SystemEnergy system_energy(const SparseMatrix& A, const Eigen::MatrixXd& b) {
  // ½ xᵀAx − bᵀx column by column (A is symmetric: column j of A times x is (Ax)_j), in parallel
  // with a deterministic reduction: monitors evaluate it at every check of million-row solves.
  return [&A, &b](const Eigen::MatrixXd& x) {
#if FAIRSHAPE_WITH_TBB
    return tbb::parallel_deterministic_reduce(
        tbb::blocked_range<Eigen::Index>(0, A.outerSize(), 4096), 0.0,
        [&](const tbb::blocked_range<Eigen::Index>& r, double acc) {
          // One pass over column j for all of x's columns (independent sums, one read of A).
          Eigen::VectorXd Ax(x.cols());
          for (Eigen::Index j = r.begin(); j != r.end(); ++j) {
            Ax.setZero();
            for (SparseMatrix::InnerIterator it(A, j); it; ++it)
              for (Eigen::Index c = 0; c < x.cols(); ++c) Ax[c] += it.value() * x(it.row(), c);
            for (Eigen::Index c = 0; c < x.cols(); ++c) acc += x(j, c) * (0.5 * Ax[c] - b(j, c));
          }
          return acc;
        },
        std::plus<double>());
#else
    double acc = 0.0;
    Eigen::VectorXd Ax(x.cols());
    for (Eigen::Index j = 0; j != A.outerSize(); ++j) {
      Ax.setZero();
      for (SparseMatrix::InnerIterator it(A, j); it; ++it)
        for (Eigen::Index c = 0; c < x.cols(); ++c) Ax[c] += it.value() * x(it.row(), c);
      for (Eigen::Index c = 0; c < x.cols(); ++c) acc += x(j, c) * (0.5 * Ax[c] - b(j, c));
    }
    return acc;
#endif
  };
}

bool IterationMonitor::record(int iteration, double residual, const Eigen::MatrixXd& x) {
  summary_.iterations = iteration;
  summary_.residual = residual;
  last_residual_ = residual;
  if (estimates_error() && !krylov_) {
    // A stationary iteration's error decays geometrically: e_k ≈ Δ_k q/(1 − q), q the ratio of
    // successive steps (meaningful once the steps contract).
    const Timer estimating;
    if (previous_x_.size() == x.size()) {
      const double step = (x - previous_x_).norm(), size = std::max(x.norm(), 1e-300);
      if (previous_step_ > 0 && step < previous_step_) {
        const double q = step / previous_step_;
        summary_.error_estimate = step * q / (1 - q) / size;
      }
      previous_step_ = step;
    }
    previous_x_ = x;
    summary_.observe_s += estimating.seconds();
  }
  const bool first = first_residual_ < 0;
  if (first) first_residual_ = residual;
  const bool energy_rule = opt_.energy_tolerance > 0;
  // One clock read where this observation starts: the solve time so far is that instant less
  // every earlier observation, so it cannot include any of this one's work.
  const double observe_start = timer_.seconds();
  const double energy = (energy_rule || cb_) ? energy_(x) : std::nan("");
  // Relative to the decrease so far, so a constant in the energy (the reduced system drops
  // one) does not change when the rule fires.
  const bool stalled = energy_rule && !first &&
                       std::abs(last_energy_ - energy) <= opt_.energy_tolerance * std::abs(first_energy_ - energy);
  if (first) first_energy_ = energy;
  last_energy_ = energy;
  if (!std::isfinite(residual) || residual > 1e12 * std::max(first_residual_, 1.0)) {
    fail("diverged at iteration " + std::to_string(iteration) + " (residual " + std::to_string(residual) + ")");
    return false;
  }
  // Never below the last record's: the observation intervals are measured by other reads of
  // the same clock, and their rounding must not make the reported time step back.
  const double solving_s = std::max(last_solving_s_, observe_start - summary_.observe_s);
  last_solving_s_ = solving_s;
  const bool stop = cb_ && !cb_({iteration, residual, solving_s, energy, &x});
  summary_.observe_s += timer_.seconds() - observe_start;
  if (stop) {
    summary_.message = "stopped by the callback";
    return false;
  }
  const bool residual_met = opt_.tolerance > 0 && residual <= opt_.tolerance;
  if (!estimates_error() && residual_met) {
    summary_.termination = Termination::Converged;
    return false;
  }
  if (estimates_error() && !krylov_ && summary_.error_estimate >= 0 &&
      summary_.error_estimate <= opt_.error_tolerance && (opt_.tolerance == 0 || residual_met)) {
    char text[160];
    std::snprintf(text, sizeof text, "relative error estimate %.3g <= %.3g (the steps' geometric tail)",
                  summary_.error_estimate, opt_.error_tolerance);
    summary_.termination = Termination::Converged;
    summary_.message = text;
    return false;
  }
  if (stalled) {
    summary_.termination = Termination::EnergyStalled;
    return false;
  }
  if (iteration >= opt_.max_iterations && summary_.termination == Termination::MaxIterations) {
    char text[160];
    if (estimates_error())
      std::snprintf(text, sizeof text, "the iteration cap (%d) came before the error tolerance %.3g: error estimate %.3g, "
                    "relative residual %.3g", opt_.max_iterations, opt_.error_tolerance, summary_.error_estimate, residual);
    else
      std::snprintf(text, sizeof text, "the iteration cap (%d) came before the tolerance %.3g: relative residual %.3g",
                    opt_.max_iterations, opt_.tolerance, residual);
    summary_.message = text;
  }
  return iteration < opt_.max_iterations;
}

// Restarts from the true residual allowed after the recursive one met the tolerance: each must
// at least halve the true residual, or rounding has the last word (measured on the cow's level-5
// edit: recursive 1e-10, true 4.1e-10 after 132 multigrid-CG iterations).
constexpr int kMaxResidualReplacements = 5;
constexpr double kRoundingSlack = 2.0;

bool IterationMonitor::confirm_residual(int iteration, double true_residual) {
  if (summary_.termination != Termination::Converged || !(opt_.tolerance > 0) || estimates_error()) return false;
  if (true_residual <= opt_.tolerance) {
    last_residual_ = true_residual;
    summary_.residual = true_residual;
    return false;
  }
  const bool progress = replaced_residual_ < 0 || true_residual < 0.5 * replaced_residual_;
  if (progress && replacements_ < kMaxResidualReplacements && iteration < opt_.max_iterations) {
    ++replacements_;
    replaced_residual_ = true_residual;
    summary_.termination = Termination::MaxIterations;  // not met yet: the cap, if it comes first, says so
    return true;
  }
  // A restart that cannot lower it shows the floor of b − Ax in double precision; within twice the
  // tolerance that is the tolerance met up to rounding (the PETSc solvers' rule too), and said.
  char text[240];
  const bool at_floor = true_residual <= kRoundingSlack * opt_.tolerance;
  std::snprintf(text, sizeof text,
                "the true relative residual stays at %.3g after %d restart(s) from it, %s the tolerance %.3g (the "
                "recursive residual met it: the rounding floor of this system)",
                true_residual, replacements_, at_floor ? "within twice" : "above", opt_.tolerance);
  summary_.termination = at_floor ? Termination::Converged : Termination::Stalled;
  summary_.residual = true_residual;
  summary_.message = text;
  return false;
}

bool IterationMonitor::record_error(int iteration, double relative_error) {
  summary_.iterations = iteration;
  summary_.error_estimate = relative_error;
  if (!estimates_error() || relative_error > opt_.error_tolerance) return true;
  if (opt_.tolerance > 0 && !(last_residual_ >= 0 && last_residual_ <= opt_.tolerance)) return true;
  char text[160];
  std::snprintf(text, sizeof text, "relative A-norm error estimate %.3g <= %.3g (Hestenes-Stiefel, %d iterations late)",
                relative_error, opt_.error_tolerance, opt_.error_delay);
  summary_.termination = Termination::Converged;
  summary_.message = text;
  return false;
}

std::string diagonal_problem(const Eigen::VectorXd& diag) {
  for (Eigen::Index i = 0; i < diag.size(); ++i)
    if (!(diag[i] > 0))
      return "row " + std::to_string(i) + " has diagonal " + std::to_string(diag[i]) +
             " <= 0: the system is singular or indefinite (is anything fixed?)";
  return "";
}

}  // namespace fairshape
