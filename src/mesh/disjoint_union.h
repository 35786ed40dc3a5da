// Several meshes as one, each a separate component: what a multi-sheet design writes as one
// polydata per step.
#pragma once

#include <vector>

#include "fairshape/mesh/surface_mesh.h"

namespace fairshape {

//! The meshes in order, vertex and face ids offset; a vertex_data array every mesh has (same
//! column count) is concatenated, the others are left out.
SurfaceMesh disjoint_union(const std::vector<SurfaceMesh>& meshes);

}  // namespace fairshape
