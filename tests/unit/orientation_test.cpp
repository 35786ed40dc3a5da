// Folds and reversed normals measured on a result (mesh/orientation.h,
// design/orientation_check.h): what the checks count on hand-made results whose answer is known.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include "fairshape/design/edit_solve.h"
#include "fairshape/design/multires_constraints.h"
#include "fairshape/design/orientation_check.h"
#include "fairshape/mesh/orientation.h"
#include "test_support.h"

using namespace fairshape;

namespace {

int center_vertex(const SurfaceMesh& m) {
  int best = 0;
  for (int v = 0; v < m.n_vertices(); ++v)
    if ((m.position(v) - Vec3(0.5, 0.5, 0)).norm() < (m.position(best) - Vec3(0.5, 0.5, 0)).norm()) best = v;
  return best;
}

}  // namespace

TEST_CASE("a rigid motion flips no face, a mirror image flips every one", "[orientation]") {
  const SurfaceMesh m = test::grid(6);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(1.2, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  MatrixX3 moved = m.positions() * R.transpose();
  moved.rowwise() += Eigen::RowVector3d(3, -1, 2);
  const FoldReport rigid = flipped_faces(m, moved);
  CHECK(rigid.flipped.empty());
  CHECK(rigid.faces == m.n_faces());
  CHECK(rigid.describe().empty());
  MatrixX3 mirrored = m.positions();
  mirrored.col(0) *= -1;  // a reflection turns the orientation of every face
  CHECK(flipped_faces(m, mirrored).flipped.size() == static_cast<std::size_t>(m.n_faces()));
}

TEST_CASE("a vertex pushed through its neighbours folds exactly the faces around it", "[orientation]") {
  const SurfaceMesh m = test::grid(6);
  const int v = center_vertex(m);
  MatrixX3 folded = m.positions();
  // Moved sideways by three edge lengths: the four quads around it turn over, the rest do not.
  folded.row(v) += Eigen::RowVector3d(0.5, 0, 0);
  const FoldReport r = flipped_faces(m, folded);
  REQUIRE(!r.flipped.empty());
  const std::vector<int> around = m.vertex_faces(v);
  for (int f : r.flipped) CHECK(std::find(around.begin(), around.end(), f) != around.end());
  CHECK(r.largest_turn_deg > 90);
  CHECK((r.center - m.position(v)).norm() < 0.5);
  CHECK_THAT(r.describe(), Catch::Contains("faces flipped"));
  // A small bump of the same vertex out of the plane turns no face over.
  MatrixX3 bump = m.positions();
  bump(v, 2) += 0.05;
  CHECK(flipped_faces(m, bump).flipped.empty());
}

TEST_CASE("the normal a normal constraint achieves keeps its sign (a mirrored surface shows the reverse)", "[orientation]") {
  const SurfaceMesh m = test::grid(6);
  NormalConstraint nc;
  nc.vertex = center_vertex(m);
  nc.normal = Vec3::UnitZ();
  const Vec3 rest = achieved_normal(m, m.positions(), nc);
  // Oriented like the faces (the grid's faces face +z), whatever order its tangents come in.
  CHECK(rest.dot(vector_area(m, m.positions(), m.vertex_faces(nc.vertex).front())) > 0);
  MatrixX3 mirrored = m.positions();
  mirrored.col(0) *= -1;
  const Vec3 after = achieved_normal(m, mirrored, nc);
  // The mirrored plane is the same plane, so the rows Q_u·N = Q_v·N = 0 still hold — and the
  // achieved normal is the reverse of the rest one.
  CHECK(std::abs(after.dot(rest) + 1) < 1e-12);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.3, Vec3::UnitX()).toRotationMatrix();
  const Vec3 turned = achieved_normal(m, m.positions() * R.transpose(), nc);
  CHECK((turned - R * rest).norm() < 1e-12);  // a rotation turns it with the surface
}

TEST_CASE("a patch of triangles given by corners folds where its mesh does", "[orientation]") {
  // The sparse feature runs' form of the check: the same answer as flipped_faces on a triangle mesh.
  const SurfaceMesh m = test::grid(6, true);
  std::vector<std::array<int, 3>> triangles;
  for (int f = 0; f < m.n_faces(); ++f) {
    const std::vector<int> c = m.face_vertices(f);
    REQUIRE(c.size() == 3);
    triangles.push_back({c[0], c[1], c[2]});
  }
  MatrixX3 folded = m.positions();
  folded.row(center_vertex(m)) += Eigen::RowVector3d(0.5, 0, 0);
  const FoldReport whole = flipped_faces(m, folded);
  const FoldReport patch = flipped_triangles(triangles, m.positions(), folded);
  REQUIRE(!whole.flipped.empty());
  CHECK(patch.flipped == whole.flipped);
  CHECK(patch.faces == whole.faces);
  CHECK((patch.center - whole.center).norm() < 1e-12);
  CHECK(flipped_triangles(triangles, m.positions(), m.positions()).flipped.empty());
  triangles.push_back({0, 1, static_cast<int>(m.n_vertices())});  // a corner past the vertices
  CHECK_THROWS_AS(flipped_triangles(triangles, m.positions(), folded), InvalidInput);
}

TEST_CASE("a drag's kept check reports what a fresh check of each step's surface reports", "[orientation]") {
  // StepOrientationCheck reuses one synthesized surface and the rest areas across calls: each
  // call must still be the check of that step alone, whatever came before it.
  const MultiresSurface rest(test::grid(4), {}, 2, Backend::Optimized);
  const int level = 1, v = center_vertex(rest.mesh(level));
  DesignConstraints placed;
  NormalConstraint nc;
  nc.level = level;
  nc.vertex = v;
  nc.normal = Vec3::UnitZ();
  placed.normals.push_back(nc);
  StepOrientationCheck step(rest, level, placed);
  for (const double push : {0.0, 0.6, 0.05, 0.6, 0.0}) {
    Eigen::MatrixXd delta = Eigen::MatrixXd::Zero(rest.mesh(level).n_vertices(), 3);
    delta(v, 0) = push;  // 0.6 drags the vertex across its neighbours: a fold
    const OrientationCheck kept = step(delta);
    const OrientationCheck fresh = check_orientation(rest, with_deformation(rest, level, delta), placed);
    CHECK(kept.folds.flipped == fresh.folds.flipped);
    CHECK(kept.folded() == fresh.folded());
    CHECK(kept.normal_error_deg == Approx(fresh.normal_error_deg).margin(1e-12));
    CHECK((step.edited().mesh(2).positions() - with_deformation(rest, level, delta).mesh(2).positions()).norm() < 1e-12);
    if (push == 0.6) CHECK(!kept.folds.flipped.empty());
    if (push == 0.0) CHECK(!kept.folded());
  }
}
