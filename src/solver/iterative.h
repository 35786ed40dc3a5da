// What every iterative solver shares: its options and the loop bookkeeping (tolerance,
// iteration cap, divergence and NaN detection, callbacks).
#pragma once

#include "fairshape/core/config.h"
#include "fairshape/core/timer.h"
#include "fairshape/solver/solver.h"

namespace fairshape {

// Stopping rules. Boier-Martin et al. run a fixed number of sweeps (tolerance 0,
// energy_tolerance 0: exactly max_iterations); a residual tolerance and an energy-change
// tolerance are the alternatives their §6 leaves as future work.
struct IterativeOptions {
  double tolerance = 1e-8;      // on the relative residual ‖b − A x‖ / ‖b‖; 0 disables
  double energy_tolerance = 0;  // stop when the last check's energy decrease ≤ this × the total decrease; 0 disables
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
  IterationMonitor(const IterativeOptions& opt, const IterationCallback& cb, SystemEnergy energy)
      : opt_(opt), cb_(cb), energy_(std::move(energy)) {
    // Reaching the cap is the stopping rule itself only when no tolerance was asked for
    // (the papers' fixed sweep counts); otherwise it means the tolerance was not reached.
    const bool tolerance_asked = opt.tolerance > 0 || opt.energy_tolerance > 0;
    summary_.termination = tolerance_asked ? Termination::MaxIterations : Termination::ScheduleCompleted;
  }
  //! Records the residual after `iteration` sweeps; false when the loop must stop.
  bool record(int iteration, double residual, const Eigen::MatrixXd& x);
  //! Whether record() looks at x (energy rule or a callback): solvers that keep their own
  //! layout convert their iterate only then.
  bool wants_iterate() const { return opt_.energy_tolerance > 0 || static_cast<bool>(cb_); }
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
  double first_residual_ = -1;
  double first_energy_ = 0, last_energy_ = 0;
  SolveSummary summary_;
};

// Checks the diagonal before a Gauss-Seidel/Jacobi sweep: a non-positive entry means the
// system is singular or indefinite (e.g. nothing pinned under a translation-invariant energy).
std::string diagonal_problem(const Eigen::VectorXd& diag);

}  // namespace fairshape
