// A quad-dominant base for Catmull-Clark: neighbouring triangles paired into quads. Catmull-
// Clark splits a triangle into three quads around a new valence-3 vertex, so a triangle base
// leaves an extraordinary vertex in every base face (and 3 of 4 corners of its children
// irregular); a quad's children are regular inside. Pairing is greedy, best-shaped pair first;
// a triangle without a good partner stays a triangle.
#pragma once

#include "fairshape/mesh/surface_mesh.h"

namespace fairshape {

struct QuadPairing {
  int max_corner_deviation_deg = 60;  // a quad corner between 30° and 150°
  int max_fold_deg = 60;              // the angle between the two triangles' normals
};

//! \throw InvalidInput for a mesh that is not all triangles.
SurfaceMesh pair_triangles(const SurfaceMesh& triangles, const QuadPairing& opt = {});

}  // namespace fairshape
