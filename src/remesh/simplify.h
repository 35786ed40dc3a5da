// Edge-collapse simplification that keeps the mesh manifold (CGAL Surface_mesh_simplification,
// Lindstrom-Turk placement, the link condition on every collapse). Its own translation unit:
// CGAL's headers are expensive to compile.
#pragma once

#include "mesh/surface_mesh.h"

namespace fairshape {

//! A triangle mesh simplified to about `target_faces` faces. \throw InvalidInput for
//! non-triangle input or a result fairshape's mesh core refuses.
SurfaceMesh simplify_to_faces(const SurfaceMesh& triangles, int target_faces);

}  // namespace fairshape
