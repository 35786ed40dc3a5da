// What a figure draws over a surface edit's result: where its constraints are.
#pragma once

#include <string>

#include "fairshape/constraint/constraint.h"
#include "fairshape/subdivision/multires_surface.h"

namespace fairshape {

//! vtk/<run>_constraints.vtp (io/constraint_overlay.h): each placed constraint at its vertex of
//! the edited surface — fixed, a handle with its offset, a normal target — and each curve
//! constraint's chain as a polyline.
void write_constraint_overlay(const DesignConstraints& placed, const MultiresSurface& edited, const std::string& path);

}  // namespace fairshape
