// What a figure draws over a surface edit's result: where its constraints are.
#pragma once

#include <string>

#include "constraint/constraint.h"
#include "subdivision/multires_surface.h"

namespace fairshape {

//! vtk/<run>_constraints.vtp: one point per placed constraint, at its vertex of the edited
//! surface, with point arrays `kind` (0 a fixed vertex, 1 a handle that moves, 2 a normal
//! target), `offset` (a handle's prescribed displacement: its arrow runs from the point minus
//! the offset to the point) and `target_normal`; each curve constraint's chain as a polyline.
void write_constraint_overlay(const DesignConstraints& placed, const MultiresSurface& edited, const std::string& path);

}  // namespace fairshape
