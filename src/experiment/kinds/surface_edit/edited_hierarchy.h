// A surface edit applied to a hierarchy and nothing else written: what another run kind needs
// to combine Boier-Martin et al.'s detail-preserving editor with its own layer (the feature
// curves of Khodakovsky & Schröder, which ride on the edited surface).
#pragma once

#include "fairshape/core/summary.h"
#include "fairshape/experiment/kinds/surface_edit/surface_edit_spec.h"
#include "fairshape/subdivision/multires_surface.h"

namespace fairshape {

struct EditedHierarchy {
  MultiresSurface edited;  // the edit level moved, the finer levels re-synthesized with their local details
  SolveSummary summary;
};

//! The edit `spec` describes (energies, constraints with or without regions of influence, the
//! edit level, the constraint mode and solver) solved on `rest`. The §5 ladder and the
//! rotation-aware rounds are not supported here. The result is checked as a surface-edit run's:
//! a fold or a reversed normal ends `folded` (normals with rows `auto` are solved again with
//! frame rows first). \throw InvalidInput naming what is not
//! supported or what the constraints' placement refuses; SolverError from the solve.
EditedHierarchy edited_hierarchy(SurfaceEditSpec& spec, const MultiresSurface& rest);

}  // namespace fairshape
