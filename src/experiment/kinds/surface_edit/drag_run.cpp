#include "fairshape/experiment/kinds/surface_edit/drag_run.h"

#include <cmath>
#include <filesystem>

#include "fairshape/core/config.h"
#include "fairshape/core/timer.h"
#include "fairshape/experiment/metric_format.h"
#include "fairshape/problem/constrained_system.h"

namespace fairshape {

std::vector<double> drag_scales(int steps) {
  std::vector<double> s;
  for (int k = 1; k <= steps; ++k) s.push_back(static_cast<double>(k) / steps);
  return s;
}

SolverFactory ladder_direct_solver(Backend backend) {
  return [backend] {
    Config none;
    return components().solvers.create("cholesky", backend, none);
  };
}

SolverFactory ladder_relaxer(const AccuracyOptions& a, Backend backend) {
  // The cascade's smoother: a fixed count, no residual checks (the paper's fixed iterations).
  return [&a, backend] {
    YAML::Node n;
    n["max_iterations"] = a.relaxation_sweeps;
    n["check_every"] = a.relaxation_sweeps;
    n["tolerance"] = 0.0;
    n["sor"]["omega"] = a.relaxation_omega;
    Config c(n, "problem.relaxation");
    return components().solvers.create(a.relaxation, backend, c);
  };
}

PassLadder pass_ladder(const SurfaceEditSpec& spec, Solver* finest) {
  const AccuracyOptions& a = spec.accuracy;
  return {a.ladder(), a.coarse_level, ladder_direct_solver(spec.implementation),
          ladder_relaxer(a, spec.implementation), finest, a.coarse_constraint_mode};
}

DragOutcome run_drag(const SurfaceEditSpec& spec, const RunOutputs& out, const EditLadder& ladder,
                     const std::vector<const ReferenceSolution*>& references, const IterationCallback& last_step,
                     bool write_steps, const StepCheck& check, const StepCallback& on_step) {
  const AccuracyOptions& a = spec.accuracy;
  const Backend backend = spec.implementation;
  MultilevelEdit edit(ladder, a.ladder(), ladder_direct_solver(backend), ladder_relaxer(a, backend), *spec.solver, backend,
                      a.coarse_constraint_mode);
  const std::vector<double> scales = drag_scales(a.drag_steps);
  DragOutcome result;
  for (std::size_t s = 0; s < scales.size(); ++s) {
    const bool last = s + 1 == scales.size();
    result.last = edit.solve(scales[s], last ? last_step : IterationCallback());
    const ReferenceSolution* ref = references[s];
    // A step that failed (or a reference that did) has no error to report: the cell stays empty
    // rather than a NaN a plot would draw as a gap or a reader take for a number.
    const bool failed = !result.last.delta.allFinite() || result.last.summary.termination == Termination::NumericalFailure;
    const bool measurable = ref && !failed && ref->u.allFinite();
    // Every step is a surface the designer sees: a fold on the way is said even when the last
    // step's surface is clean (papers/boier-martin/README.md, "Folds and reversed normals").
    std::string flipped, check_s;
    if (!failed && !last && check) {
      const Timer timer;
      const OrientationCheck c = check(result.last.delta);
      check_s = num(timer.seconds());
      flipped = std::to_string(c.folds.flipped.size());
      if (c.folded())
        result.folded_steps += (result.folded_steps.empty() ? "" : ", ") + std::to_string(s + 1) + " (" +
                               (c.folds.flipped.empty() ? "a reversed normal" : flipped + " faces") + ")";
    }
    if (on_step && result.last.delta.allFinite()) on_step(static_cast<int>(s) + 1, result.last.delta);
    if (write_steps)
      out.add_row("steps", {std::to_string(s + 1), num(scales[s]), std::string(to_string(a.ladder())), num(result.last.solve_s),
                   std::to_string(result.last.summary.iterations),
                   measurable ? num(relative_error(result.last.delta, ref->u)) : "",
                   std::isfinite(result.last.constraint_residual) ? num(result.last.constraint_residual) : "",
                   ref ? num(ref->solve_s) : "", flipped, check_s});
    if (failed) break;  // the later steps would start from nothing; the run reports this one's failure
  }
  result.level_solutions = edit.level_solutions();
  return result;
}

}  // namespace fairshape
