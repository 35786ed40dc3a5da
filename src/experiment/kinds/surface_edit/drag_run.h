// A run's design steps through its session (design/surface_edit_session.h): problem.drag_steps'
// equal steps of the configured offsets (a drag: the handles move from the rest shape to them,
// each step warm-started from the last) or the `steps:` list, solved in turn. Every step is a
// row of steps.csv beside CHOLMOD's prefactored solve of the same step.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "fairshape/design/surface_edit_session.h"
#include "fairshape/experiment/kinds/surface_edit/surface_edit_spec.h"
#include "fairshape/experiment/run_outputs.h"

namespace fairshape {

// CHOLMOD's solution of a run's system and the time of its solve with the factor in hand.
struct ReferenceSolution {
  Eigen::MatrixXd u;
  double solve_s = 0;
};

struct StepsOutcome {
  SurfaceEditStep last;  // the final step: the surface the run asked for
  //! Earlier steps whose surface folded (what the designer saw on the way), "" when none.
  std::string folded_steps;
};

//! Called after each step k = 1..n that produced a surface, with the session holding it.
using StepCallback = std::function<void(int step, const SurfaceEditSession& session)>;

//! spec.steps solved on `session` in turn. `references[k]` is CHOLMOD's solution of step k (or
//! null); `last_step` receives the final step's iterations. steps.csv gets a row per step when
//! `write_steps`, with the flipped faces the session found on every step before the last (the
//! run's own columns report the last) and the time of its checks. A failed step ends the steps.
StepsOutcome run_steps(const SurfaceEditSpec& spec, const RunOutputs& out, SurfaceEditSession& session,
                       const std::vector<const ReferenceSolution*>& references, const IterationCallback& last_step,
                       bool write_steps, const StepCallback& on_step = {});

}  // namespace fairshape
