#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

#include "fairshape/io/mesh_io.h"
#include "fairshape/remesh/closest_point.h"
#include "fairshape/remesh/quad_pairing.h"
#include "fairshape/remesh/quality.h"
#include "fairshape/remesh/remesh.h"
#include "fairshape/remesh/simplify.h"
#include "test_support.h"

using namespace fairshape;

namespace {

// A triangulated torus (major radius R, minor r), nu × nv quads each split in two.
SurfaceMesh torus(int nu, int nv, double R = 1.0, double r = 0.4) {
  MatrixX3 V(nu * nv, 3);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * std::numbers::pi * i / nu, v = 2 * std::numbers::pi * j / nv;
      V.row(i * nv + j) << (R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v);
    }
  PolygonList F;
  auto id = [nu, nv](int i, int j) { return (i % nu) * nv + (j % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      F.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      F.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return SurfaceMesh::from_polygons(V, F);
}

double total_area(const SurfaceMesh& m) {
  double a = 0;
  for (int f = 0; f < m.n_faces(); ++f) {
    const auto vs = m.face_vertices(f);
    for (std::size_t i = 1; i + 1 < vs.size(); ++i)
      a += 0.5 * (m.position(vs[i]) - m.position(vs[0])).cross(m.position(vs[i + 1]) - m.position(vs[0])).norm();
  }
  return a;
}

}  // namespace

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

TEST_CASE("facing points skip the far side of a thin part", "[remesh]") {
  // Two parallel sheets 0.1 apart, facing away from each other (a thin slab's top and bottom):
  // the bottom sheet's normals point down (-z), the top sheet's up.
  SurfaceMesh top = test::grid(4, true);
  MatrixX3 V(2 * top.n_vertices(), 3);
  V << top.positions(), top.positions();
  V.bottomRows(top.n_vertices()).col(2).array() -= 0.1;
  PolygonList F = top.polygons();
  for (auto f : top.polygons()) {
    std::reverse(f.begin(), f.end());
    for (int& v : f) v += top.n_vertices();
    F.push_back(f);
  }
  const ClosestPointQuery q(SurfaceMesh::from_polygons(V, F));
  MatrixX3 p(2, 3), n(2, 3);
  p << 0.5, 0.5, -0.04,  // nearer the top sheet, but it wants a surface facing down
      0.5, 0.5, -0.04;
  n << 0, 0, -1, 0, 0, 1;
  int unmoved = -1;
  const MatrixX3 c = q.facing_points(p, n, 1.0, &unmoved);
  CHECK((c.row(0) - Eigen::RowVector3d(0.5, 0.5, -0.1)).norm() <= 1e-12);
  CHECK((c.row(1) - Eigen::RowVector3d(0.5, 0.5, 0.0)).norm() <= 1e-12);
  CHECK(unmoved == 0);
  // Out of reach: the plain closest point (the top sheet), and counted.
  const MatrixX3 far = q.facing_points(p.topRows(1), n.topRows(1), 0.01, &unmoved);
  CHECK((far.row(0) - Eigen::RowVector3d(0.5, 0.5, 0.0)).norm() <= 1e-12);
  CHECK(unmoved == 1);
}

TEST_CASE("quality report: known distances, edge lengths and valences", "[remesh]") {
  // A unit square of 4 × 4 quads, and the same square lifted by 0.03: every point of either
  // is exactly 0.03 from the other.
  const SurfaceMesh a = test::grid(4);
  SurfaceMesh b = test::grid(4, true);
  b.positions().col(2).array() += 0.03;
  const ClosestPointQuery on_a(a), on_b(b);
  const SurfaceDistance d = hausdorff_distance(a, on_a, b, on_b, 0.01);
  CHECK(d.a_to_b == Approx(0.03).epsilon(1e-12));
  CHECK(d.b_to_a == Approx(0.03).epsilon(1e-12));
  // Samples cover faces, not just vertices: a bump in the middle of a face is seen.
  SurfaceMesh bump = test::grid(1);  // one quad, no vertex near its centre
  const SurfaceMesh flat = bump;
  MatrixX3 V(5, 3);
  V << bump.positions(), 0.5, 0.5, 0.2;
  const SurfaceMesh pyramid = SurfaceMesh::from_polygons(V, {{0, 1, 4}, {1, 3, 4}, {3, 2, 4}, {2, 0, 4}});
  const ClosestPointQuery on_flat(flat), on_pyramid(pyramid);
  const SurfaceDistance dp = hausdorff_distance(flat, on_flat, pyramid, on_pyramid, 0.01);
  CHECK(dp.b_to_a == Approx(0.2).epsilon(1e-12));      // the apex
  CHECK(dp.a_to_b == Approx(0.2 * 0.5 / std::hypot(0.5, 0.2)).epsilon(0.02));  // the flat centre to the slopes
  // Edge lengths of a 4 × 2 grid stretched to 2 × 1: cells 0.5 × 0.5; diagonals of the
  // triangulated one are longer by √2.
  SurfaceMesh g = test::grid(4, true);
  g.positions().col(0) *= 2.0;
  const EdgeLengthRange e = edge_length_range(g);
  CHECK(e.shortest == Approx(0.25));
  CHECK(e.longest == Approx(std::hypot(0.5, 0.25)));
  CHECK(e.ratio() == Approx(std::hypot(0.5, 0.25) / 0.25));
  // Valences of an open 4 × 4 quad grid: 4 corners of 2, 12 boundary vertices of 3, 9 inner of 4.
  const ValenceHistogram h = valence_histogram(test::grid(4));
  CHECK(h == ValenceHistogram{{2, 4}, {3, 12}, {4, 9}});
  CHECK(to_string(h) == "2:4 3:12 4:9");
}

TEST_CASE("pairing triangles into quads keeps the surface and its topology", "[remesh]") {
  const SurfaceMesh tri = torus(30, 12);
  const SurfaceMesh q = pair_triangles(tri);
  int quads = 0, triangles = 0;
  for (int f = 0; f < q.n_faces(); ++f) (q.face_size(f) == 4 ? quads : triangles) += 1;
  CHECK(quads + triangles == q.n_faces());
  CHECK(2 * quads + triangles == tri.n_faces());  // every triangle used once
  CHECK(quads >= 0.9 * tri.n_faces() / 2);        // a regular strip pairs almost completely
  CHECK(q.n_vertices() - q.n_edges() + q.n_faces() == 0);  // still a torus
  CHECK(q.boundary_loops().empty());
  CHECK(total_area(q) == Approx(total_area(tri)).epsilon(1e-2));  // fan-split quads: non-planar ones differ slightly
}

TEST_CASE("simplification keeps a closed mesh manifold, closed and of the same genus", "[remesh]") {
  for (const char* file : {"cow.off", "knot.off"}) {
    const SurfaceMesh dense = read_mesh(test::data_path(file));
    for (int target : {200, 600}) {
      INFO(file << " " << target);
      for (const SurfaceMesh& base : {simplify_to_faces(dense, target), isotropic_base(dense, target)}) {
        CHECK(std::abs(base.n_faces() - target) <= target / 10 + 2);
        CHECK(base.boundary_loops().empty());
        CHECK(base.n_vertices() - base.n_edges() + base.n_faces() ==
              dense.n_vertices() - dense.n_edges() + dense.n_faces());
      }
    }
  }
}

TEST_CASE("remesh of a smooth torus: close to it, even edges, mostly regular", "[remesh]") {
  const SurfaceMesh dense = torus(60, 24);
  struct Case {
    SchemeType scheme;
    BaseMethod base;
    double max_ratio;  // measured (Catmull-Clark / Loop): 15.9 / 12.5 edge collapse, 6.9 / 3.1 isotropic
  };
  for (const Case& c : {Case{SchemeType::CatmullClark, BaseMethod::EdgeCollapse, 30.0},
                        Case{SchemeType::Loop, BaseMethod::EdgeCollapse, 25.0},
                        Case{SchemeType::CatmullClark, BaseMethod::Isotropic, 12.0},
                        Case{SchemeType::Loop, BaseMethod::Isotropic, 6.0}}) {
    INFO(to_string(c.scheme) << (c.base == BaseMethod::Isotropic ? " isotropic" : " edge collapse"));
    RemeshOptions opt;
    opt.subdivision.scheme = c.scheme;
    opt.base_method = c.base;
    opt.base_faces = 200;
    opt.levels = 3;
    opt.sample_spacing = 3e-3;
    RemeshReport r;
    const MultiresSurface h = remesh(dense, opt, &r);
    CHECK(std::abs(r.base_faces - 200) <= 30);
    CHECK(r.hausdorff_relative() <= 0.003);  // measured 0.12-0.17 %
    CHECK(r.edge_ratio() <= c.max_ratio);
    // The report describes the hierarchy returned.
    CHECK(r.fine_vertices == h.mesh(3).n_vertices());
    CHECK(r.base_valence == valence_histogram(h.mesh(0)));
    CHECK(r.edge_ratio() == Approx(edge_length_range(h.mesh(3)).ratio()));
    const int regular = c.scheme == SchemeType::CatmullClark ? 4 : 6;
    CHECK(r.fine_valence.at(regular) >= 0.9 * r.fine_vertices);
    if (c.scheme == SchemeType::CatmullClark) {  // a quad-dominant base: mostly quads
      int quads = 0;
      for (int f = 0; f < h.mesh(0).n_faces(); ++f) quads += h.mesh(0).face_size(f) == 4;
      CHECK(quads >= 0.6 * h.mesh(0).n_faces());
    }
  }
}

TEST_CASE("remesh: the finest level lies on the dense surface and synthesis reproduces it", "[remesh]") {
  const SurfaceMesh dense = read_mesh(test::data_path("cow.off"));
  const ClosestPointQuery on_dense(dense);
  for (SchemeType scheme : {SchemeType::CatmullClark, SchemeType::Loop}) {
    INFO(to_string(scheme));
    RemeshOptions opt;
    opt.subdivision.scheme = scheme;
    opt.base_faces = 200;
    opt.levels = 2;
    opt.sample_spacing = 3e-3;
    RemeshReport r;
    const MultiresSurface h = remesh(dense, opt, &r);
    const MatrixX3& fine = h.mesh(2).positions();
    // On the dense surface, except the vertices the fit held back (keep_even_moves) where
    // landing would crowd or stretch their edges: the report counts those and bounds them.
    const Eigen::VectorXd off = (fine - on_dense.closest_points(fine)).rowwise().norm();
    CHECK((off.array() > 1e-9 * r.bbox_diagonal).count() == r.off_surface);
    CHECK(r.off_surface < fine.rows() / 20);  // 2-4 % at this coarse size (cow, 200 faces, 2 levels)
    CHECK(off.maxCoeff() == Approx(r.off_surface_max).margin(1e-12));
    CHECK(off.maxCoeff() <= r.fine_to_dense + r.sample_spacing);
    // Re-synthesis from the base and the local details gives the same finest level.
    MultiresSurface again = h;
    again.synthesize(DetailSpace::Local);
    CHECK((again.mesh(2).positions() - fine).rowwise().norm().maxCoeff() <= 1e-9 * r.bbox_diagonal);
    CHECK(r.hausdorff > 0);
    CHECK(r.hausdorff_relative() < 0.03);  // 2.7 % both (the 1.5 % target is not met at this size: warned)
    // The dense-side distances are real: a coarser base fits worse.
    RemeshOptions coarse = opt;
    coarse.base_faces = 30;
    coarse.levels = 1;
    RemeshReport rc;
    remesh(dense, coarse, &rc);
    CHECK(rc.hausdorff > r.hausdorff);
  }
}

TEST_CASE("remesh refuses bad requests", "[remesh]") {
  const SurfaceMesh dense = read_mesh(test::data_path("cow.off"));
  RemeshOptions opt;
  opt.base_faces = 2;
  CHECK_THROWS_WITH(remesh(dense, opt, nullptr), Catch::Matchers::Contains("--base-faces 2 outside [4, 5804]"));
  opt.base_faces = 100000;
  CHECK_THROWS_AS(remesh(dense, opt, nullptr), InvalidInput);
  opt.base_faces = 10;
  CHECK_THROWS_WITH(remesh(test::grid(4), opt, nullptr), Catch::Matchers::Contains("needs a triangle mesh"));
}
