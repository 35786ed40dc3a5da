#include "fairshape/experiment/kinds/surface_edit/edited_hierarchy.h"

#include "fairshape/core/error.h"

namespace fairshape {

EditedHierarchy edited_hierarchy(SurfaceEditSpec& spec, const MultiresSurface& rest) {
  if (spec.accuracy.multilevel())
    throw InvalidInput("problem.accuracy: only single-level edits combine with other layers (the ladder of §5 is a run of its own)");
  if (spec.rotations.iterations > 0)
    throw InvalidInput("problem.rotation_iterations: rotation-aware rounds do not combine with other layers");
  const int level = spec.edit_level < 0 ? rest.levels() : spec.edit_level;
  const EditTerms terms = spec.edit_terms();
  if (is_regional(terms)) {
    RegionalEditResult r = solve_regional_edit(terms, rest, level, spec.constraint_mode, *spec.solver, spec.implementation,
                                               spec.qp_config(), spec.constraint_tolerance);
    return {std::move(r.edited), r.summary};
  }
  DesignConstraints placed;
  const EditLadder ladder = assemble_edit_ladder(terms, rest, level, level, placed);
  const EditSolution sol = solve_edit(ladder.problems.back(), spec.constraint_mode, *spec.solver, spec.implementation, {}, nullptr,
                                      spec.qp_config());
  EditedHierarchy out{rest, sol.summary};
  if (sol.delta.allFinite() && sol.summary.termination != Termination::NumericalFailure) {
    out.edited.set_level_positions(level, rest.mesh(level).positions() + MatrixX3(sol.delta));
    out.edited.synthesize_from(level, DetailSpace::Local);
  }
  return out;
}

}  // namespace fairshape
