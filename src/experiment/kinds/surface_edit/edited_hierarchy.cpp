#include "fairshape/experiment/kinds/surface_edit/edited_hierarchy.h"

#include "fairshape/core/error.h"
#include "fairshape/experiment/kinds/surface_edit/open_session.h"

namespace fairshape {

EditedHierarchy edited_hierarchy(SurfaceEditSpec& spec, const MultiresSurface& rest) {
  if (spec.accuracy.multilevel())
    throw InvalidInput("problem.accuracy: only single-level edits combine with other layers (the ladder of §5 is a run of its own)");
  if (spec.rotations.iterations > 0)
    throw InvalidInput("problem.rotation_iterations: rotation-aware rounds do not combine with other layers");
  // The session checks its result as a surface-edit run's is (a fold or a reversed normal ends
  // `folded`: the layers above would hide it), normals with rows `auto` solved again with frame
  // rows first (design/orientation_check.h).
  const std::unique_ptr<SurfaceEditSession> session = open_session(spec, borrowed(rest), true);
  const SurfaceEditStep step = session->solve();
  return {session->current(), step.summary};
}

}  // namespace fairshape
