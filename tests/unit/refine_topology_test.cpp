#include <catch2/catch.hpp>

#include "fairshape/io/mesh_io.h"
#include "fairshape/subdivision/subdivider.h"
#include "test_support.h"

using namespace fairshape;

TEST_CASE("direct child connectivity equals child_faces and is a valid half-edge mesh", "[subdivision]") {
  std::vector<SurfaceMesh> meshes{read_mesh(test::data_path("mushroom.off")), read_mesh(test::data_path("knot.off")),
                                  test::grid(3, true), test::grid(1, true)};
  std::vector<SurfaceMesh> polygon_meshes{read_mesh(test::data_path("double-torus-example.off")), test::grid(3),
                                          read_mesh(test::data_path("3torus.off"))};
  for (SchemeType scheme : {SchemeType::CatmullClark, SchemeType::Loop})
    for (const auto& m : scheme == SchemeType::Loop ? meshes : polygon_meshes) {
      INFO(to_string(scheme) << " " << m.n_faces() << " faces");
      SurfaceMesh fine = refine_topology(m, scheme, CreaseMethod::Uniform);
      test::check_halfedge_invariants(fine);
      CHECK(fine.polygons() == child_faces(m, scheme));
      CHECK(fine.boundary_loops().size() == m.boundary_loops().size());
      // Two steps deep, the same holds (the child is itself a valid parent).
      SurfaceMesh finer = refine_topology(fine, scheme, CreaseMethod::Uniform);
      test::check_halfedge_invariants(finer);
      CHECK(finer.polygons() == child_faces(fine, scheme));
    }
  for (const auto& m : meshes) {  // Catmull-Clark on triangles too
    test::check_halfedge_invariants(refine_topology(m, SchemeType::CatmullClark, CreaseMethod::Uniform));
    CHECK(refine_topology(m, SchemeType::CatmullClark, CreaseMethod::Uniform).polygons() == child_faces(m, SchemeType::CatmullClark));
  }
}
