#include "fairshape/experiment/kinds/surface_edit/edited_hierarchy.h"

#include "fairshape/core/error.h"
#include "fairshape/design/orientation_check.h"

namespace fairshape {

namespace {

// One solve of the edit, its result checked for folds and reversed normals as a surface-edit
// run's is (design/orientation_check.h).
EditedHierarchy solve_once(SurfaceEditSpec& spec, const MultiresSurface& rest, int level, OrientationCheck& checked) {
  const EditTerms terms = spec.edit_terms();
  checked = {};
  if (is_regional(terms)) {
    RegionalEditResult r = solve_regional_edit(terms, rest, level, spec.constraint_mode, *spec.solver, spec.implementation,
                                               spec.qp_config(), spec.constraint_tolerance);
    if (is_success(r.summary.termination)) checked = check_orientation(rest, r.edited, r.placed);
    return {std::move(r.edited), r.summary};
  }
  DesignConstraints placed;
  const EditLadder ladder = assemble_edit_ladder(terms, rest, level, level, placed);
  const EditSolution sol = solve_edit(ladder.problems.back(), spec.constraint_mode, *spec.solver, spec.implementation, {}, nullptr,
                                      spec.qp_config());
  EditedHierarchy out{rest, sol.summary};
  if (sol.delta.allFinite() && sol.summary.termination != Termination::NumericalFailure) {
    out.edited = with_deformation(rest, level, sol.delta);
    checked = check_orientation(rest, out.edited, placed);
  }
  return out;
}

}  // namespace

EditedHierarchy edited_hierarchy(SurfaceEditSpec& spec, const MultiresSurface& rest) {
  if (spec.accuracy.multilevel())
    throw InvalidInput("problem.accuracy: only single-level edits combine with other layers (the ladder of §5 is a run of its own)");
  if (spec.rotations.iterations > 0)
    throw InvalidInput("problem.rotation_iterations: rotation-aware rounds do not combine with other layers");
  const int level = spec.edit_level < 0 ? rest.levels() : spec.edit_level;
  OrientationCheck checked;
  EditedHierarchy out{rest, {}};
  const std::string note = solve_orienting_normals([&](bool frame_rows) {
    spec.frame_rows_for_auto_normals = frame_rows;
    out = solve_once(spec, rest, level, checked);
    return checked;
  });
  spec.frame_rows_for_auto_normals = false;
  out.summary.message = noted(note, out.summary.message);
  if (checked.folded() && is_success(out.summary.termination)) {  // the layers above would hide it
    out.summary.termination = Termination::Folded;
    out.summary.message = noted(out.summary.message, checked.describe());
  }
  return out;
}

}  // namespace fairshape
