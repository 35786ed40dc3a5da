// Coarse triangle meshes of a dense one (CGAL; its own translation unit, because CGAL's
// headers are expensive to compile).
#pragma once

#include "fairshape/mesh/surface_mesh.h"

namespace fairshape {

//! Edge-collapse simplification to about `target_faces` faces that keeps the mesh manifold
//! (Surface_mesh_simplification, Lindstrom-Turk placement, the link condition on every collapse).
//! \throw InvalidInput for non-triangle input or a result fairshape's mesh core refuses.
SurfaceMesh simplify_to_faces(const SurfaceMesh& triangles, int target_faces);

//! A near-equilateral triangle mesh of about `target_faces` faces on the dense surface (CGAL's
//! isotropic remeshing: split, collapse, flip towards valence 6, tangential relaxation,
//! projection onto the input). Edge collapse leaves slivers and long thin triangles whose
//! subdivisions keep that anisotropy on every level; this base has even edges to start from.
//! \throw InvalidInput as simplify_to_faces.
SurfaceMesh isotropic_base(const SurfaceMesh& triangles, int target_faces);

}  // namespace fairshape
