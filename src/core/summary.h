// One outcome vocabulary for every solve and every run (linear solvers, constrained QPs,
// length-constrained curve solves, whole experiment runs): how it stopped, and whether
// that is what was asked.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace fairshape {

// Success:
//   converged          — the tolerance that was asked for was met;
//   energy_stalled     — the configured energy_tolerance rule fired (a documented stopping rule);
//   schedule_completed — no tolerance was asked: a fixed procedure (the papers' fixed sweep
//                        counts, the interactive ladder) ran to its end.
// Failure:
//   max_iterations     — a tolerance was asked and the iteration cap came first;
//   constraints_unmet  — the solve ended, but the result misses its constraints by more than
//                        the tolerance asked (measured on the result, not on the linear rows);
//   not_a_minimum      — constraints and stationarity met, but the point is a constrained saddle:
//                        the Lagrangian's Hessian has negative curvature on the constraints'
//                        tangent space (a step along it, projected back, lowers the objective);
//   folded             — the constraints are met, but the result turns the surface over: faces
//                        flipped against the surface they came from, or a normal constraint
//                        met by the reverse of its target (its rows, tangents ⊥ N, hold for −N
//                        as well);
//   stalled            — an iterative solve stopped making progress (no decrease of its measure
//                        over the stall window) before its tolerance: more iterations would not help;
//   infeasible         — no point satisfying the constraints was found from the start (the
//                        constraints' residual could not be driven to the tolerance);
//   ill_conditioned    — the constraints are met, but they are nearly dependent with
//                        conflicting targets, so the answer is dominated by the conflict
//                        (an exact solve moving a vertex far beyond every handle);
//   numerical_failure  — diverged, singular, non-finite, or the result fails its own checks;
//   invalid_input      — the input (files, constraints) made the run impossible;
//   output_failed      — the result could not be written (disk full, permissions);
//   crashed            — an unexpected exception or a signal ended the run;
//   edit_undone        — the solve met its constraints, but not the edit: the handles the user
//                        dragged were pulled back (a drag asking more length than the curve has)
//                        or the result returned them most of the way to where they started.
enum class Termination {
  Converged,
  EnergyStalled,
  ScheduleCompleted,
  MaxIterations,
  ConstraintsUnmet,
  IllConditioned,
  NumericalFailure,
  NotAMinimum,
  Folded,
  Stalled,
  Infeasible,
  InvalidInput,
  OutputFailed,
  Crashed,
  OutOfMemory,
  EditUndone
};

std::string_view to_string(Termination t);
//! \throw InvalidInput naming the valid choices for an unknown name.
Termination termination_from_string(std::string_view name);
//! The run delivered what was asked (see the table above).
bool is_success(Termination t);
//! Every name, in declaration order (for docs and errors).
const std::vector<std::string>& termination_names();

// What every solver reports, whatever it solves.
struct SolveSummary {
  Termination termination = Termination::NumericalFailure;
  int iterations = 0;
  double residual = -1;  // relative: ‖b − A x‖ / ‖b‖ (−1: not measured)
  std::string message;
  //! Seconds spent observing the iterations (energies, callbacks, iterate copies for them):
  //! callers subtract it, so a monitored solve is timed like an unmonitored one.
  double observe_s = 0;
  //! Relative error estimate of the answer (solver/iterative.h: the A-norm for conjugate
  //! gradients, the steps' geometric tail for stationary solvers); −1: not estimated.
  double error_estimate = -1;
  bool succeeded() const { return is_success(termination); }
};

}  // namespace fairshape
