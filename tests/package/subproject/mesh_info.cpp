// Counts of a mesh built by hand, through fairshape::mesh of a fairshape built by add_subdirectory.
#include <fairshape/mesh/surface_mesh.h>

#include <iostream>

int main() {
  fairshape::MatrixX3 v(4, 3);
  v << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  const fairshape::SurfaceMesh quad = fairshape::SurfaceMesh::from_polygons(v, {{0, 1, 2, 3}});
  std::cout << quad.n_vertices() << " vertices, " << quad.n_faces() << " face\n";
  return quad.n_vertices() == 4 && quad.n_faces() == 1 ? 0 : 1;
}
