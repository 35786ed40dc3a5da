#include <catch2/catch.hpp>

#include "io/mesh_io.h"
#include "remesh/closest_point.h"
#include "remesh/remesh.h"
#include "remesh/simplify.h"
#include "test_support.h"

using namespace fairshape;

TEST_CASE("closest points on a plane and a triangle", "[remesh]") {
  const ClosestPointQuery q(test::grid(4, true));
  MatrixX3 p(3, 3);
  p << 0.3, 0.7, 2.0,     // above the unit square: drops straight down
      -1.0, 0.5, 0.0,     // beside it: clamps to the edge x = 0
      2.0, 2.0, -1.0;     // beyond a corner: the corner
  const MatrixX3 c = q.closest_points(p);
  CHECK((c.row(0) - Eigen::RowVector3d(0.3, 0.7, 0)).norm() <= 1e-14);
  CHECK((c.row(1) - Eigen::RowVector3d(0, 0.5, 0)).norm() <= 1e-14);
  CHECK((c.row(2) - Eigen::RowVector3d(1, 1, 0)).norm() <= 1e-14);
}

TEST_CASE("simplification keeps a closed mesh manifold, closed and of the same genus", "[remesh]") {
  for (const char* file : {"cow.off", "knot.off"}) {
    const SurfaceMesh dense = read_mesh(test::data_path(file));
    for (int target : {200, 600}) {
      INFO(file << " " << target);
      const SurfaceMesh base = simplify_to_faces(dense, target);
      CHECK(std::abs(base.n_faces() - target) <= target / 10 + 2);
      CHECK(base.boundary_loops().empty());
      CHECK(base.n_vertices() - base.n_edges() + base.n_faces() ==
            dense.n_vertices() - dense.n_edges() + dense.n_faces());
    }
  }
}

TEST_CASE("remesh: finest level on the dense surface, analysis exact, Hausdorff reported", "[remesh]") {
  const SurfaceMesh dense = read_mesh(test::data_path("cow.off"));
  for (SchemeType scheme : {SchemeType::CatmullClark, SchemeType::Loop}) {
    RemeshOptions opt;
    opt.subdivision.scheme = scheme;
    opt.base_faces = 400;
    opt.levels = 2;
    RemeshReport r;
    const MultiresSurface h = remesh(dense, opt, &r);
    CHECK(h.levels() == 2);
    CHECK(r.rms_fine_to_dense <= 1e-12 * r.bbox_diagonal);  // projected, then reproduced exactly
    CHECK(r.hausdorff > 0);
    CHECK(r.hausdorff < 0.1 * r.bbox_diagonal);
    // The dense-side distances are real: a coarser base fits worse.
    RemeshOptions coarse = opt;
    coarse.base_faces = 60;
    RemeshReport rc;
    remesh(dense, coarse, &rc);
    CHECK(rc.hausdorff > r.hausdorff);
  }
}

TEST_CASE("remesh refuses bad requests", "[remesh]") {
  const SurfaceMesh dense = read_mesh(test::data_path("cow.off"));
  RemeshOptions opt;
  opt.base_faces = 2;
  CHECK_THROWS_WITH(remesh(dense, opt, nullptr), Catch::Matchers::Contains("--base-faces 2 outside"));
  opt.base_faces = 100000;
  CHECK_THROWS_AS(remesh(dense, opt, nullptr), InvalidInput);
  opt.base_faces = 10;
  CHECK_THROWS_WITH(remesh(test::grid(4), opt, nullptr), Catch::Matchers::Contains("needs a triangle mesh"));
}
