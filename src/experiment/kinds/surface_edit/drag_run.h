// A run of the accuracy ladder (problem.accuracy, design/multilevel_edit.h) as a drag: the
// handles move from the rest shape to their configured offsets in problem.drag_steps equal
// steps, each solved with the same constraint set and warm-started from the last. Every
// step is a row of steps.csv beside CHOLMOD's prefactored solve of the same step.
#pragma once

#include <functional>
#include <vector>

#include "fairshape/design/multilevel_edit.h"
#include "fairshape/design/orientation_check.h"
#include "fairshape/design/regional_edit.h"
#include "fairshape/experiment/kinds/surface_edit/run_one.h"

namespace fairshape {

//! The ladder's coarse (and bounded-region) solver: CHOLMOD.
SolverFactory ladder_direct_solver(Backend backend);
//! The improved cascade's relaxation on each finer level: problem.relaxation with a fixed
//! count (problem.relaxation_sweeps), no residual checks. `a` must outlive the factory.
SolverFactory ladder_relaxer(const AccuracyOptions& a, Backend backend);

//! The ladder of a run with regions of influence (design/regional_edit.h), as configured;
//! `finest` is the converged mode's solver. Only for spec.accuracy.multilevel().
PassLadder pass_ladder(const SurfaceEditSpec& spec, Solver* finest);

//! s / steps for s = 1..steps.
std::vector<double> drag_scales(int steps);

struct DragOutcome {
  EditSolution last;                            // the final step (scale 1)
  std::vector<Eigen::MatrixXd> level_solutions;  // its deformation on each level of the ladder
  //! Earlier steps whose surface folded (what the designer saw on the way), "" when none.
  std::string folded_steps;
};

//! Called after each step s = 1..steps (after its check) with its edit-level deformation (e.g. to write it).
using StepCallback = std::function<void(int step, const Eigen::MatrixXd& delta)>;
//! The orientation check of a step's edit-level deformation (its surface synthesized).
using StepCheck = std::function<OrientationCheck(const Eigen::MatrixXd& delta)>;

//! `references[s]` is CHOLMOD's solution of step s (or null); `last_step` receives the final
//! step's iterations. steps.csv gets a row per step when `write_steps`, with the flipped faces
//! `check` finds on every step before the last (the run's own check measures the last) and
//! the check's time.
DragOutcome run_drag(const SurfaceEditSpec& spec, const RunOutputs& out, const EditLadder& ladder,
                     const std::vector<const ReferenceSolution*>& references, const IterationCallback& last_step,
                     bool write_steps, const StepCheck& check, const StepCallback& on_step = {});

}  // namespace fairshape
