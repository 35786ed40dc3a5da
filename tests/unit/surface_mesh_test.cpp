#include <catch2/catch.hpp>

#include "fairshape/io/mesh_io.h"
#include "fairshape/mesh/mesh_stats.h"
#include "test_support.h"

using namespace fairshape;

using test::check_halfedge_invariants;

TEST_CASE("half-edge invariants and topology of every bundled mesh", "[mesh]") {
  for (const auto& k : test::bundled_meshes()) {
    INFO(k.file);
    const MeshFile raw = read_mesh_file(test::data_path(k.file));
    const SurfaceMesh m = SurfaceMesh::from_polygons(raw.vertices, raw.faces);
    check_halfedge_invariants(m);
    CHECK(m.polygons() == raw.faces);  // ids and corner order are kept
    const MeshStats s = compute_stats(m);
    CHECK(s.genus == k.genus);
    CHECK(s.boundary_loops == k.boundary_loops);
    CHECK(s.components == 1);
  }
}

TEST_CASE("open grid: boundary loop, valences and Euler characteristic", "[mesh]") {
  const SurfaceMesh m = test::grid(4);
  check_halfedge_invariants(m);
  const auto loops = m.boundary_loops();
  REQUIRE(loops.size() == 1);
  CHECK(loops[0].size() == 16);
  CHECK(m.valence(0) == 2);   // corner
  CHECK(m.valence(1) == 3);   // boundary edge vertex
  CHECK(m.valence(6) == 4);   // interior
  CHECK(m.is_boundary_vertex(0));
  CHECK_FALSE(m.is_boundary_vertex(6));
  const MeshStats s = compute_stats(m);
  CHECK(s.euler_characteristic == 1);
  CHECK(s.genus == 0);
  // A corner belonging to exactly one face has one face in its fan.
  CHECK(m.vertex_faces(0).size() == 1);
}

TEST_CASE("one-ring traversal is ordered: consecutive neighbours share a face", "[mesh]") {
  const SurfaceMesh m = read_mesh(test::data_path("cow.off"));
  for (int v = 0; v < m.n_vertices(); v += 97) {
    const auto hs = m.outgoing_halfedges(v);
    for (std::size_t k = 0; k < hs.size(); ++k) {
      const int h = hs[k], next_out = hs[(k + 1) % hs.size()];
      CHECK(m.rotate_ccw(h) == next_out);
      // Consecutive spokes bound one face, the one left of h.
      const auto fv = m.face_vertices(m.face(h));
      CHECK(std::count(fv.begin(), fv.end(), m.to_vertex(next_out)) == 1);
    }
  }
}

TEST_CASE("several boundary loops and isolated vertices are reported", "[mesh]") {
  // A quad strip closed into an annulus has two boundary loops; vertex 8 is unused.
  MatrixX3 V(9, 3);
  for (int i = 0; i < 4; ++i) {
    const double a = i * M_PI / 2;
    V.row(i) << std::cos(a), std::sin(a), 0;
    V.row(i + 4) << 2 * std::cos(a), 2 * std::sin(a), 0;
  }
  V.row(8) << 9, 9, 9;
  PolygonList F;
  for (int i = 0; i < 4; ++i) F.push_back({i, (i + 1) % 4, 4 + (i + 1) % 4, 4 + i});
  const SurfaceMesh m = SurfaceMesh::from_polygons(V, F);
  const MeshStats s = compute_stats(m);
  CHECK(s.boundary_loops == 2);
  CHECK(s.isolated_vertices == 1);
  CHECK(s.euler_characteristic == 0);
  CHECK(s.genus == 0);
  CHECK(m.is_isolated(8));
}

TEST_CASE("validation rejects bad meshes with the offending ids named", "[mesh]") {
  const MatrixX3 tri = (MatrixX3(4, 3) << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0).finished();
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(SurfaceMesh::from_polygons(MatrixX3(0, 3), {}), Contains("no vertices"));
  CHECK_THROWS_WITH(SurfaceMesh::from_polygons(tri, {}), Contains("no faces"));
  CHECK_THROWS_WITH(SurfaceMesh::from_polygons(tri, {{0, 1}}), Contains("face 0 has 2 vertices"));
  CHECK_THROWS_WITH(SurfaceMesh::from_polygons(tri, {{0, 1, 1}}), Contains("repeats a vertex"));
  CHECK_THROWS_WITH(SurfaceMesh::from_polygons(tri, {{0, 1, 7}}), Contains("vertex 7, out of range"));
  CHECK_THROWS_WITH(SurfaceMesh::from_polygons(tri, {{0, 1, 2}, {1, 2, 3}}), Contains("inconsistent orientation"));
  MatrixX3 nan = tri;
  nan(2, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(SurfaceMesh::from_polygons(nan, {{0, 1, 2}}), Contains("vertex 2 has a NaN"));
  const MatrixX3 five = (MatrixX3(5, 3) << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1).finished();
  CHECK_THROWS_WITH(SurfaceMesh::from_polygons(five, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}), Contains("non-manifold edge"));
  CHECK_THROWS_WITH(SurfaceMesh::from_polygons(five, {{0, 1, 2}, {0, 3, 4}}), Contains("non-manifold vertex"));
}
