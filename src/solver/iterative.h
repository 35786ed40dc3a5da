// What every iterative solver shares: its options and the loop bookkeeping (tolerance,
// iteration cap, divergence and NaN detection, callbacks).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "fairshape/core/config.h"
#include "fairshape/core/timer.h"
#include "fairshape/solver/solver.h"

namespace fairshape {

// Stopping rules. Boier-Martin et al. run a fixed number of sweeps (tolerance 0,
// energy_tolerance 0: exactly max_iterations); a residual tolerance and an energy-change
// tolerance are the alternatives their §6 leaves as future work.
// A small residual is not a small error on a fourth-order system (measured: at a million
// vertices the error of an iterate floors near 1e-7 while its residual keeps falling), so a
// solve can also stop on an estimate of its relative error: conjugate gradients (plain and
// multigrid-preconditioned) by the Hestenes-Stiefel lower bound of the A-norm error,
// ‖x − x_k‖²_A ≥ Σ_{j=k}^{k+d−1} α_j (r_j, z_j), evaluated d iterations late (Strakoš and Tichý,
// "On error estimation in the conjugate gradient method and why it works in finite precision
// computations"); the stationary solvers (Gauss-Seidel, SOR, multigrid cycles) by the
// geometric tail of their steps, ‖Δ_k‖ q/(1 − q) with q = ‖Δ_k‖/‖Δ_{k−1}‖. Both are estimates,
// not bounds, and are reported as such.
struct IterativeOptions {
  double tolerance = 1e-8;      // on the relative residual ‖b − A x‖ / ‖b‖; 0 disables
  double energy_tolerance = 0;  // stop when the last check's energy decrease ≤ this × the total decrease; 0 disables
  double error_tolerance = 0;   // stop when the relative error estimate ≤ this; 0 disables
  int error_delay = 5;          // CG: iterations between an iterate and its error estimate (d above)
  int max_iterations = 1000;
  int check_every = 1;  // residual evaluations cost about one sweep: check less often on big systems
  static IterativeOptions from_config(Config& cfg);
};

// SOR relaxation factor, shared by both back ends' `sor` solver.
double sor_omega_from_config(Config& cfg);

//! ½ Σ_c x_cᵀ A x_c − b_cᵀ x_c, the quadratic the solver minimizes.
using SystemEnergy = std::function<double(const Eigen::MatrixXd& x)>;
SystemEnergy system_energy(const SparseMatrix& A, const Eigen::MatrixXd& b);

class IterationMonitor {
 public:
  //! `energy` is evaluated only when the energy rule is on or a callback listens.
  //! `krylov`: the solver estimates its error itself (record_error); otherwise, with an error
  //! tolerance, record() estimates it from the iterates' steps.
  IterationMonitor(const IterativeOptions& opt, const IterationCallback& cb, SystemEnergy energy, bool krylov = false)
      : opt_(opt), cb_(cb), energy_(std::move(energy)), krylov_(krylov) {
    // Reaching the cap is the stopping rule itself only when no tolerance was asked for
    // (the papers' fixed sweep counts); otherwise it means the tolerance was not reached.
    const bool tolerance_asked = opt.tolerance > 0 || opt.energy_tolerance > 0 || opt.error_tolerance > 0;
    summary_.termination = tolerance_asked ? Termination::MaxIterations : Termination::ScheduleCompleted;
  }
  //! Records the residual after `iteration` sweeps; false when the loop must stop.
  bool record(int iteration, double residual, const Eigen::MatrixXd& x);
  //! A Krylov solver's relative error estimate of its current iterate; false when it is within
  //! the error tolerance (and the residual tolerance, when one was asked for too).
  bool record_error(int iteration, double relative_error);
  bool estimates_error() const { return opt_.error_tolerance > 0; }
  //! A Krylov solver whose recursive residual met the tolerance (record() returned false with
  //! `converged`) gives the true relative residual ‖b − Ax‖/‖b‖ here: true when it misses the
  //! tolerance and a restart from it may still reach it (the caller replaces its residual by
  //! the true one and restarts its directions); false to stop — converged if the true residual
  //! meets the tolerance (or, at a floor restarts cannot lower, twice the tolerance: rounding, said
  //! in the message), otherwise `stalled`, saying where the true residual floors.
  bool confirm_residual(int iteration, double true_residual);
  //! Whether record() looks at x (energy rule or a callback): solvers that keep their own
  //! layout convert their iterate only then.
  bool wants_iterate() const {
    return opt_.energy_tolerance > 0 || static_cast<bool>(cb_) || (estimates_error() && !krylov_);
  }
  bool should_check(int iteration) const {
    return iteration % opt_.check_every == 0 || iteration == opt_.max_iterations;
  }
  SolveSummary summary() const { return summary_; }
  //! Runs the solver's preparation of an observation (e.g. converting its iterate for
  //! record()), counted as observing, not solving.
  template <class Prepare>
  void observe(Prepare&& prepare) {
    const Timer t;
    prepare();
    summary_.observe_s += t.seconds();
  }
  void fail(const std::string& message) {
    summary_.termination = Termination::NumericalFailure;
    summary_.message = message;
  }

 private:
  IterativeOptions opt_;
  const IterationCallback& cb_;
  Timer timer_;
  SystemEnergy energy_;
  bool krylov_ = false;
  double first_residual_ = -1;
  double last_residual_ = -1;
  double last_solving_s_ = 0;  // the seconds of the last record
  Eigen::MatrixXd previous_x_;  // stationary solvers with an error tolerance: the last check's iterate
  double previous_step_ = -1;
  double first_energy_ = 0, last_energy_ = 0;
  int replacements_ = 0;             // confirm_residual's restarts so far
  double replaced_residual_ = -1;    // the true residual at the last restart
  SolveSummary summary_;
};

//! The Hestenes-Stiefel estimate of CG's relative A-norm error: push each iteration's
//! Σ_columns α (r, z); once `delay` terms are in, estimate() is the error of the iterate `delay`
//! iterations back (the current one's is smaller: CG's A-norm error only falls), relative to
//! ‖x‖_A with xᵀAx = xᵀ(b − r) from CG's own residual (no extra product).
class CgErrorEstimate {
 public:
  explicit CgErrorEstimate(int delay) : delay_(static_cast<std::size_t>(delay)) {}
  void push(double alpha_rz) {
    terms_.push_back(alpha_rz);
    if (terms_.size() > delay_) terms_.erase(terms_.begin());
  }
  bool ready() const { return terms_.size() == delay_; }
  double estimate(double x_A_norm_squared) const {
    double tail = 0;
    for (double t : terms_) tail += t;  // d terms, summed afresh: no cancellation from a running sum
    return std::sqrt(std::max(tail, 0.0) / std::max(x_A_norm_squared, 1e-300));
  }

 private:
  std::size_t delay_;
  std::vector<double> terms_;
};

// Checks the diagonal before a Gauss-Seidel/Jacobi sweep: a non-positive entry means the
// system is singular or indefinite (e.g. nothing pinned under a translation-invariant energy).
std::string diagonal_problem(const Eigen::VectorXd& diag);

}  // namespace fairshape
