#include "solver/iterative.h"

#include <cmath>

namespace fairshape {

std::string_view to_string(Termination t) {
  switch (t) {
    case Termination::Converged: return "converged";
    case Termination::MaxIterations: return "max_iterations";
    case Termination::NumericalFailure: return "numerical_failure";
    case Termination::InvalidInput: return "invalid_input";
  }
  return "unknown";
}

IterativeOptions IterativeOptions::from_config(Config& cfg) {
  IterativeOptions o;
  o.tolerance = cfg.get_number("tolerance", o.tolerance, 0.0, 1.0, "relative residual to stop at");
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

bool IterationMonitor::record(int iteration, double residual, const Eigen::MatrixXd& x) {
  summary_.iterations = iteration;
  summary_.residual = residual;
  if (first_residual_ < 0) first_residual_ = residual;
  if (!std::isfinite(residual) || residual > 1e12 * std::max(first_residual_, 1.0)) {
    fail("diverged at iteration " + std::to_string(iteration) + " (residual " + std::to_string(residual) + ")");
    return false;
  }
  if (cb_ && !cb_({iteration, residual, timer_.seconds(), &x})) {
    summary_.message = "stopped by the callback";
    return false;
  }
  if (residual <= opt_.tolerance) {
    summary_.termination = Termination::Converged;
    return false;
  }
  return iteration < opt_.max_iterations;
}

std::string diagonal_problem(const Eigen::VectorXd& diag) {
  for (Eigen::Index i = 0; i < diag.size(); ++i)
    if (!(diag[i] > 0))
      return "row " + std::to_string(i) + " has diagonal " + std::to_string(diag[i]) +
             " <= 0: the system is singular or indefinite (is anything fixed?)";
  return "";
}

}  // namespace fairshape
