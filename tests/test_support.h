// Paths and small fixtures shared by the Catch2 tests.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "fairshape/mesh/surface_mesh.h"

namespace fairshape::test {

inline std::string source_path(const std::string& rel) { return std::string(FAIRSHAPE_SOURCE_DIR) + "/" + rel; }
inline std::string data_path(const std::string& name) { return source_path("data/" + name); }

// The scratch folder for `name` under the build tree, unique per name and per test case: ctest
// runs test cases as parallel processes, and a helper shared by several cases (one fixed name)
// would otherwise let one case wipe or overwrite the files another is reading.
inline std::filesystem::path scratch_path(const std::string& name) {
  const std::string test_case = Catch::getResultCapture().getCurrentTestName();
  return std::filesystem::path(FAIRSHAPE_BINARY_DIR) / "test-scratch" / name /
         std::to_string(std::hash<std::string>{}(test_case));
}
// scratch_path(name), emptied.
inline std::filesystem::path scratch_dir(const std::string& name) {
  const auto dir = scratch_path(name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Bundled meshes with their known topology.
struct KnownMesh {
  std::string file;
  int genus, boundary_loops;
};
inline std::vector<KnownMesh> bundled_meshes() {
  return {{"cow.off", 0, 0},           {"mushroom.off", 0, 1}, {"knot.off", 1, 0},
          {"double-torus-example.off", 2, 0}, {"3torus.off", 3, 0}, {"torus_quad.off", 1, 0},
          {"cross_quad.off", 0, 0},    {"fandisk.off", 0, 0},  {"hand.off", 0, 0}};
}

// An open (n+1) x (n+1) grid of quads in the z = 0 plane, optionally split into triangles.
inline SurfaceMesh grid(int n, bool triangles = false) {
  MatrixX3 V((n + 1) * (n + 1), 3);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) V.row(j * (n + 1) + i) << double(i) / n, double(j) / n, 0.0;
  PolygonList F;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      if (triangles) {
        F.push_back({a, b, c});
        F.push_back({a, c, d});
      } else {
        F.push_back({a, b, c, d});
      }
    }
  return SurfaceMesh::from_polygons(V, F);
}

// The half-edge invariants every mesh must satisfy.
inline void check_halfedge_invariants(const SurfaceMesh& m) {
  for (int h = 0; h < m.n_halfedges(); ++h) {
    REQUIRE(m.twin(m.twin(h)) == h);
    REQUIRE(m.next(m.prev(h)) == h);
    REQUIRE(m.prev(m.next(h)) == h);
    REQUIRE(m.from_vertex(m.next(h)) == m.to_vertex(h));
    REQUIRE(m.face(m.next(h)) == m.face(h));
    REQUIRE(m.from_vertex(h) != m.to_vertex(h));
    REQUIRE(!(m.is_boundary_halfedge(h) && m.is_boundary_halfedge(m.twin(h))));
  }
  int outgoing_total = 0;
  for (int v = 0; v < m.n_vertices(); ++v) {
    const auto out = m.outgoing_halfedges(v);
    outgoing_total += static_cast<int>(out.size());
    for (int h : out) REQUIRE(m.from_vertex(h) == v);
    // A boundary vertex starts its fan at its boundary half-edge; no other half-edge of the fan is boundary.
    for (std::size_t k = 1; k < out.size(); ++k) REQUIRE(!m.is_boundary_halfedge(out[k]));
    REQUIRE(m.is_boundary_vertex(v) == (!out.empty() && m.is_boundary_halfedge(out[0])));
  }
  REQUIRE(outgoing_total == m.n_halfedges());
}


}  // namespace fairshape::test
