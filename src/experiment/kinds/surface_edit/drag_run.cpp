#include "fairshape/experiment/kinds/surface_edit/drag_run.h"

#include <filesystem>

#include "fairshape/core/config.h"
#include "fairshape/experiment/metric_format.h"
#include "fairshape/problem/constrained_system.h"

namespace fairshape {

std::vector<double> drag_scales(int steps) {
  std::vector<double> s;
  for (int k = 1; k <= steps; ++k) s.push_back(static_cast<double>(k) / steps);
  return s;
}

DragOutcome run_drag(const SurfaceEditSpec& spec, const RunOutputs& out, const EditLadder& ladder,
                     const std::vector<const ReferenceSolution*>& references, const IterationCallback& last_step,
                     bool write_steps, const StepCallback& on_step) {
  const AccuracyOptions& a = spec.accuracy;
  const Backend backend = spec.implementation;
  const SolverFactory direct = [backend] {
    Config none;
    return components().solvers.create("cholesky", backend, none);
  };
  // The cascade's smoother: a fixed count, no residual checks (the paper's fixed iterations).
  const SolverFactory relaxer = [&a, backend] {
    YAML::Node n;
    n["max_iterations"] = a.relaxation_sweeps;
    n["check_every"] = a.relaxation_sweeps;
    n["tolerance"] = 0.0;
    n["sor"]["omega"] = a.relaxation_omega;
    Config c(n, "problem.relaxation");
    return components().solvers.create(a.relaxation, backend, c);
  };
  MultilevelEdit edit(ladder, a.ladder(), direct, relaxer, *spec.solver, backend,
                      a.coarse_constraint_mode);
  const std::vector<double> scales = drag_scales(a.drag_steps);
  DragOutcome result;
  for (std::size_t s = 0; s < scales.size(); ++s) {
    const bool last = s + 1 == scales.size();
    result.last = edit.solve(scales[s], last ? last_step : IterationCallback());
    if (on_step && result.last.delta.allFinite()) on_step(static_cast<int>(s) + 1, result.last.delta);
    const ReferenceSolution* ref = references[s];
    if (write_steps)
      out.add_row("steps", {std::to_string(s + 1), num(scales[s]), std::string(to_string(a.ladder())), num(result.last.solve_s),
                   std::to_string(result.last.summary.iterations),
                   ref ? num(relative_error(result.last.delta, ref->u)) : "", num(result.last.constraint_residual),
                   ref ? num(ref->solve_s) : ""});
  }
  result.level_solutions = edit.level_solutions();
  return result;
}

}  // namespace fairshape
