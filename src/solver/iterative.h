// What every iterative solver shares: its options and the loop bookkeeping (tolerance,
// iteration cap, divergence and NaN detection, callbacks).
#pragma once

#include "core/config.h"
#include "core/timer.h"
#include "solver/solver.h"

namespace fairshape {

struct IterativeOptions {
  double tolerance = 1e-8;  // on the relative residual
  int max_iterations = 1000;
  int check_every = 1;  // residual evaluations cost about one sweep: check less often on big systems
  static IterativeOptions from_config(Config& cfg);
};

// SOR relaxation factor, shared by both back ends' `sor` solver.
double sor_omega_from_config(Config& cfg);

class IterationMonitor {
 public:
  IterationMonitor(const IterativeOptions& opt, const IterationCallback& cb) : opt_(opt), cb_(cb) {}
  //! Records the residual after `iteration` sweeps; false when the loop must stop.
  bool record(int iteration, double residual, const Eigen::MatrixXd& x);
  bool should_check(int iteration) const {
    return iteration % opt_.check_every == 0 || iteration == opt_.max_iterations;
  }
  SolveSummary summary() const { return summary_; }
  void fail(const std::string& message) {
    summary_.termination = Termination::NumericalFailure;
    summary_.message = message;
  }

 private:
  IterativeOptions opt_;
  const IterationCallback& cb_;
  Timer timer_;
  double first_residual_ = -1;
  SolveSummary summary_{Termination::MaxIterations, 0, -1, ""};
};

// Checks the diagonal before a Gauss-Seidel/Jacobi sweep: a non-positive entry means the
// system is singular or indefinite (e.g. nothing pinned under a translation-invariant energy).
std::string diagonal_problem(const Eigen::VectorXd& diag);

}  // namespace fairshape
