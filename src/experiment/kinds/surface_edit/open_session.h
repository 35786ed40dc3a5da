// A surface-edit spec turned into the session that solves it (design/surface_edit_session.h):
// the one place a config's problem: and solver: blocks become the session's options, for the
// run kind, the feature kind's editor and the Python module alike.
#pragma once

#include <memory>

#include "fairshape/design/surface_edit_session.h"
#include "fairshape/experiment/kinds/surface_edit/surface_edit_spec.h"

namespace fairshape {

//! The ladder's coarse (and bounded-region) solver: CHOLMOD.
SolverFactory ladder_direct_solver(Backend backend);
//! The improved cascade's relaxation on each finer level: problem.relaxation with a fixed
//! count (problem.relaxation_sweeps), no residual checks.
SolverFactory ladder_relaxer(const AccuracyOptions& a, Backend backend);

//! The ladder of a run with §5's accuracy modes, as configured; `finest` is the converged
//! mode's solver. Only for spec.accuracy.multilevel().
PassLadder pass_ladder(const SurfaceEditSpec& spec, Solver* finest);

//! The session of `spec` on `rest` (shared: a run's cache, or the session's own). `orient_normals`:
//! SurfaceEditOptions::orient_normals; the spec's frame_rows_for_auto_normals is the session's start.
//! \throw InvalidInput as the session's constructor.
std::unique_ptr<SurfaceEditSession> open_session(const SurfaceEditSpec& spec, std::shared_ptr<const MultiresSurface> rest,
                                                 bool orient_normals = true);

//! `h` lent to a session by its owner (a run's cache), which outlives the session.
inline std::shared_ptr<const MultiresSurface> borrowed(const MultiresSurface& h) {
  return std::shared_ptr<const MultiresSurface>(std::shared_ptr<const MultiresSurface>(), &h);
}

//! Applies `step`'s changes to `session` (scale first, then the handles' offsets).
void apply_step(const EditStepSpec& step, SurfaceEditSession& session);
//! Solves `step` on `session` with its mode (the session's configured one by default).
SurfaceEditStep solve_step(const EditStepSpec& step, SurfaceEditSession& session, const IterationCallback& cb = {});

}  // namespace fairshape
