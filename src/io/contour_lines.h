// Level lines of a scalar field on a surface mesh (VTK's contour filter and stripper): the
// outline of a region where the field exceeds a value, as polylines a figure can draw.
#pragma once

#include <vector>

#include "fairshape/mesh/surface_mesh.h"

namespace fairshape {

//! The polylines where the piecewise-linear field `values` (one per vertex) equals `level`,
//! each as its points in order (a closed one repeats its first point).
//! \throw InvalidInput when values does not have one entry per vertex.
std::vector<std::vector<Vec3>> contour_lines(const SurfaceMesh& mesh, const Eigen::VectorXd& values, double level);

}  // namespace fairshape
