#include "fairshape/experiment/kinds/surface_edit/drag_run.h"

#include <cmath>

#include "fairshape/experiment/kinds/surface_edit/open_session.h"
#include "fairshape/experiment/metric_format.h"
#include "fairshape/problem/constrained_system.h"

namespace fairshape {

StepsOutcome run_steps(const SurfaceEditSpec& spec, const RunOutputs& out, SurfaceEditSession& session,
                       const std::vector<const ReferenceSolution*>& references, const IterationCallback& last_step,
                       bool write_steps, const StepCallback& on_step) {
  StepsOutcome result;
  for (std::size_t s = 0; s < spec.steps.size(); ++s) {
    const bool last = s + 1 == spec.steps.size();
    apply_step(spec.steps[s], session);
    result.last = solve_step(spec.steps[s], session, last ? last_step : IterationCallback());
    const EditSolution& sol = result.last.solution;
    const ReferenceSolution* ref = references[s];
    // A step that failed (or a reference that did) has no error to report: the cell stays empty
    // rather than a NaN a plot would draw as a gap or a reader take for a number.
    const bool failed = !sol.delta.allFinite() || sol.summary.termination == Termination::NumericalFailure;
    const bool measurable = ref && !failed && ref->u.allFinite();
    // Every step is a surface the designer sees: a fold on the way is said even when the last
    // step's surface is clean (papers/boier-martin/README.md, "Folds and reversed normals").
    std::string flipped, check_s;
    if (!failed && !last) {
      const OrientationCheck& c = result.last.orientation;
      check_s = num(result.last.check_s);
      flipped = std::to_string(c.folds.flipped.size());
      if (c.folded())
        result.folded_steps += (result.folded_steps.empty() ? "" : ", ") + std::to_string(s + 1) + " (" +
                               (c.folds.flipped.empty() ? "a reversed normal" : flipped + " faces") + ")";
    }
    if (on_step && sol.delta.allFinite()) on_step(static_cast<int>(s) + 1, session);
    if (write_steps)
      out.add_row("steps", {std::to_string(s + 1), spec.steps[s].scale ? num(*spec.steps[s].scale) : "",
                            result.last.accuracy, num(sol.solve_s), std::to_string(sol.summary.iterations),
                            measurable ? num(relative_error(sol.delta, ref->u)) : "",
                            std::isfinite(sol.constraint_residual) ? num(sol.constraint_residual) : "",
                            ref ? num(ref->solve_s) : "", flipped, check_s});
    if (failed) break;  // the later steps would start from nothing; the run reports this one's failure
  }
  return result;
}

}  // namespace fairshape
