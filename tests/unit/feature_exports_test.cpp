// Issue 24 part 5: a feature curve's attachment on every finer level, and what a feature run
// exports (limit positions and normals, per-level feature displacements, attachments).
#include <catch2/catch.hpp>

#include <random>

#include "fairshape/feature/level_attachment.h"
#include "fairshape/subdivision/subdivider.h"
#include "feature_test_meshes.h"
#include "test_support.h"

using namespace fairshape;
using namespace fairshape::feature;

namespace {

// The next level's connectivity with every new vertex at its edge's midpoint: the 1:4 split of
// the parameter domain itself, on which a parameter point keeps its position.
SurfaceMesh midpoint_refined(const SurfaceMesh& coarse) {
  SurfaceMesh fine = refine_topology(coarse, SchemeType::Loop, CreaseMethod::Uniform);
  MatrixX3 X(fine.n_vertices(), 3);
  X.topRows(coarse.n_vertices()) = coarse.positions();
  for (int e = 0; e < coarse.n_edges(); ++e)
    X.row(coarse.n_vertices() + e) = 0.5 * (coarse.positions().row(coarse.from_vertex(2 * e)) + coarse.positions().row(coarse.to_vertex(2 * e)));
  fine.positions() = X;
  return fine;
}

// As TriangleSurface reads a face: its corners from face_halfedge on.
Vec3 at(const SurfaceMesh& m, const SurfacePoint& p) {
  int c[3];
  int h = m.face_halfedge(p.face);
  for (int i = 0; i < 3; ++i, h = m.next(h)) c[i] = m.from_vertex(h);
  return p.bary[0] * m.positions().row(c[0]).transpose() + p.bary[1] * m.positions().row(c[1]).transpose() +
         p.bary[2] * m.positions().row(c[2]).transpose();
}

}  // namespace

TEST_CASE("a parameter point followed to finer levels stays where it is on the split parameter domain", "[feature][exports]") {
  // A bumpy open grid: the faces are not coplanar, so a wrong child or wrong coordinates show.
  SurfaceMesh m = test::plane_grid(4, 1.0);
  MatrixX3 X = m.positions();
  for (int v = 0; v < m.n_vertices(); ++v) X(v, 2) = 0.2 * std::sin(7 * X(v, 0)) * std::cos(5 * X(v, 1));
  m.positions() = X;
  std::vector<SurfaceMesh> levels{m};
  for (int l = 0; l < 3; ++l) levels.push_back(midpoint_refined(levels.back()));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  // Corners, edges and the children's borders first, then random points.
  const std::vector<Vec3> special{{1, 0, 0}, {0.5, 0.5, 0}, {0.5, 0.25, 0.25}, {0, 0.5, 0.5}, {1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.25, 0.25, 0.5}};
  for (int k = 0; k < 200; ++k) {
    double a = u(rng), b = u(rng);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    const Vec3 bary = k < static_cast<int>(special.size()) ? special[k] : Vec3(1 - a - b, a, b);
    SurfacePoint p{static_cast<int>(k % m.n_faces()), bary};
    const Vec3 x = at(levels[0], p);
    for (int l = 1; l <= 3; ++l) {
      p = child_point(p);
      INFO("sample " << k << " level " << l);
      REQUIRE(p.face >= 0);
      REQUIRE(p.face < levels[l].n_faces());
      CHECK(p.bary.minCoeff() >= -1e-12);
      CHECK(p.bary.sum() == Approx(1).margin(1e-12));
      CHECK((at(levels[l], p) - x).norm() <= 1e-12);
    }
  }
}
