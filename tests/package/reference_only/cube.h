// The unit cube as six quads.
#pragma once

#include <fairshape/mesh/surface_mesh.h>

inline fairshape::SurfaceMesh unit_cube() {
  fairshape::MatrixX3 v(8, 3);
  v << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  return fairshape::SurfaceMesh::from_polygons(
      v, {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}});
}
