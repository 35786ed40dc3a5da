// Fine-level feature curves (feature/): the unrolled distance, the cubic cross-section, C¹ at the
// boundary of the region of influence, locality, zero features, order independence on a plane,
// rigid-motion invariance, reference = optimized, and the errors for bad curves.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "fairshape/feature/adaptive_mesh.h"
#include "fairshape/feature/featured_surface.h"
#include "fairshape/io/mesh_io.h"
#include "feature_test_meshes.h"
#include "test_support.h"

using namespace fairshape;
using namespace fairshape::feature;
using fairshape::test::cylinder;
using fairshape::test::plane_grid;

namespace {

MatrixX3 up_normals(const SurfaceMesh& m) {
  MatrixX3 n(m.n_vertices(), 3);
  n.rowwise() = Eigen::RowVector3d(0, 0, 1);
  return n;
}

FeatureCurve curve_through(const TriangleSurface& s, const std::vector<Vec3>& points, FeatureParams params,
                           int level = 0) {
  MatrixX3 m(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  return {"test", level, project_to_surface(s, m, 1e-6, "test curve"), params};
}

MultiresSurface loop_hierarchy(const SurfaceMesh& base, int levels) {
  SubdivisionOptions opt;
  opt.scheme = SchemeType::Loop;
  return MultiresSurface(base, opt, levels, Backend::Optimized);
}

}  // namespace

TEST_CASE("unrolled rays: straight on a plane, along the geodesic helix on a cylinder", "[feature]") {
  const SurfaceMesh plane = plane_grid(16, 1.0);
  const TriangleSurface flat(plane, up_normals(plane));
  const auto start = project_to_surface(flat, MatrixX3(Eigen::RowVector3d(0.23, 0.31, 0)), 1e-9, "start");
  const UnrolledRay ray = unroll_ray(flat, start[0], Vec3(1, 0.7, 0), 0.5);
  CHECK((flat.point(ray.end) - (Vec3(0.23, 0.31, 0) + 0.5 * Vec3(1, 0.7, 0).normalized())).norm() < 1e-12);
  CHECK(ray.length() == Approx(0.5).epsilon(1e-12));
  CHECK(!ray.hit_boundary);

  // On the cylinder the geodesic from (R, 0, z0) at angle θ to the axis is the helix
  // φ = L sin θ / R, z = z0 + L cos θ. The double projection at edges (rather than an exact
  // unfolding) drifts by O(h); the error must fall with the mesh size.
  const double R = 1.0, L = 2.0;
  const auto helix_error = [&](int around, double theta) {
    const SurfaceMesh cyl = cylinder(around, around / 4, R, 4.0);
    const TriangleSurface round(cyl, loop_limit_normals(cyl));
    const auto p0 = project_to_surface(round, MatrixX3(Eigen::RowVector3d(R, 0, 1.03)), 1e-3, "start");
    const UnrolledRay r = unroll_ray(round, p0[0], Vec3(0, std::sin(theta), std::cos(theta)), L);
    const Vec3 end = round.point(r.end);
    const double phi = L * std::sin(theta) / R;
    return (end - Vec3(R * std::cos(phi), R * std::sin(phi), round.point(p0[0]).z() + L * std::cos(theta))).norm();
  };
  for (double theta : {0.0, 0.4, 1.0, std::numbers::pi / 2}) {
    const double coarse = helix_error(64, theta), fine = helix_error(256, theta);
    INFO("theta " << theta << ": end point error " << coarse << " (64 around), " << fine << " (256 around)");
    CHECK(fine < 5e-3 * L);
    CHECK(fine <= 0.5 * coarse + 1e-12);
  }
}

TEST_CASE("a straight groove on a plane has exactly the cubic cross-section and is C1 at its boundary", "[feature]") {
  const int n = 64;
  const SurfaceMesh plane = plane_grid(n, 1.0);
  const TriangleSurface flat(plane, up_normals(plane));
  FeatureParams q;
  q.radius = 0.2;
  q.height = -0.03;
  q.crease = 0.1;
  const BaseCurve curve = build_base_curve(flat, curve_through(flat, {Vec3(0.2, 0.5, 0), Vec3(0.8, 0.5, 0)}, q));
  CHECK(curve.segments.size() > 10);  // split at every edge it crosses (Figure 5)
  CHECK(curve.total_length == Approx(0.6).epsilon(1e-12));
  for (Backend backend : {Backend::Reference, Backend::Optimized}) {
    const MatrixX3 d = compute_perturbation(flat, {curve}, backend).dense(plane.n_vertices());
    double worst = 0;
    for (int v = 0; v < plane.n_vertices(); ++v) {
      const Vec3 p = plane.position(v);
      CHECK(d.row(v).head<2>().norm() == 0.0);  // moves along the normal only
      if (p.x() < 0.25 || p.x() > 0.75) continue;  // beside the segment's interior
      const double y = std::abs(p.y() - 0.5);
      const double expected = y < q.radius ? cubic_profile(y, q.radius, q.height, q.crease, 0, 0) : 0.0;
      worst = std::max(worst, std::abs(d(v, 2) - expected));
    }
    CHECK(worst < 1e-12);
  }
  // C¹ at y = r: the discrete slope of the cross-section next to the boundary is within
  // h·max|f''| of zero (a profile with a kink there would keep a slope of order height / r).
  const MatrixX3 d = compute_perturbation(flat, {curve}, Backend::Optimized).dense(plane.n_vertices());
  const double h = 1.0 / n;
  const int column = n / 2;
  double max_f2 = 0;
  for (int k = 0; k <= 100; ++k) {
    const double s = q.radius * k / 100, e = 1e-5;
    max_f2 = std::max(max_f2, std::abs(cubic_profile(s + e, q.radius, q.height, q.crease, 0, 0) -
                                       2 * cubic_profile(s, q.radius, q.height, q.crease, 0, 0) +
                                       cubic_profile(std::max(s - e, 0.0), q.radius, q.height, q.crease, 0, 0)) /
                                  (e * e));
  }
  for (int j = n / 2; j < n; ++j) {
    const double y0 = static_cast<double>(j) / n - 0.5, y1 = y0 + h;
    if (y0 < q.radius && y1 >= q.radius) {
      const double slope_in = (d((j) * (n + 1) + column, 2) - d((j - 1) * (n + 1) + column, 2)) / h;
      const double slope_across = (d((j + 1) * (n + 1) + column, 2) - d(j * (n + 1) + column, 2)) / h;
      CHECK(std::abs(slope_in) <= 2 * h * max_f2);
      CHECK(std::abs(slope_across) <= h * max_f2);
    }
  }
}

TEST_CASE("zero height and crease change nothing, points beyond the region never move", "[feature]") {
  const SurfaceMesh plane = plane_grid(32, 1.0);
  const TriangleSurface flat(plane, up_normals(plane));
  FeatureParams zero;
  zero.radius = 0.2;
  zero.height = 0;
  zero.crease = 0;
  const BaseCurve c0 = build_base_curve(flat, curve_through(flat, {Vec3(0.2, 0.3, 0), Vec3(0.7, 0.6, 0)}, zero));
  CHECK(compute_perturbation(flat, {c0}, Backend::Optimized).dense(plane.n_vertices()).norm() == 0.0);

  // On a cylinder the section across the feature is a circle: the cubic through the boundary
  // conditions reproduces it up to its fourth-order term (r⁴ / 24R³ = 7e-5 here) and the sag of
  // the flat facets the ray runs on below the vertices (h² / 8R = 3e-4).
  const SurfaceMesh cyl = cylinder(128, 64, 1.0, 4.0);
  const TriangleSurface round(cyl, loop_limit_normals(cyl));
  const BaseCurve c1 = build_base_curve(round, curve_through(round, {Vec3(1, 0, 1.5), Vec3(1, 0, 2.5)}, zero, 0));
  const LevelPerturbation d1 = compute_perturbation(round, {c1}, Backend::Optimized);
  CHECK(d1.displacement.rowwise().norm().maxCoeff() < 5e-3 * zero.radius);

  // Locality on a Loop hierarchy: the drawn level moves only within r (+ one edge: the
  // control points of the neighbourhood triangles), the finest level within r plus the
  // subdivision support of the drawn level (two rings).
  FeaturedSurface fs(loop_hierarchy(plane_grid(16, 1.0), 2), Backend::Optimized);
  const SurfaceMesh& level1 = fs.original().mesh(1);
  const TriangleSurface s1(level1, loop_limit_normals(level1));
  FeatureParams bump;
  bump.radius = 0.15;
  bump.height = 0.02;
  fs.add(curve_through(s1, {Vec3(0.3, 0.4, 0), Vec3(0.6, 0.55, 0)}, bump, 1));
  const Vec3 a(0.3, 0.4, 0), b(0.6, 0.55, 0);
  const auto dist = [&](const Vec3& p) {
    const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    return (p - (a + t * (b - a))).norm();
  };
  const double h1 = 1.0 / 32;
  for (int level : {1, 2}) {
    const MatrixX3 moved = fs.result().mesh(level).positions() - fs.original().mesh(level).positions();
    const double reach = bump.radius + (level == 1 ? h1 : 2 * h1);
    int far_moved = 0, near_moved = 0;
    for (int v = 0; v < moved.rows(); ++v) {
      const double dv = dist(fs.original().mesh(level).position(v));
      if (moved.row(v).norm() > 0) (dv > reach ? far_moved : near_moved)++;
    }
    CHECK(far_moved == 0);
    CHECK(near_moved > 20);
  }
}

TEST_CASE("overlapping features on a plane do not depend on their order, deleting one loses nothing", "[feature]") {
  FeaturedSurface ab(loop_hierarchy(plane_grid(24, 1.0), 1), Backend::Optimized);
  FeaturedSurface ba(loop_hierarchy(plane_grid(24, 1.0), 1), Backend::Optimized);
  const SurfaceMesh& base = ab.original().mesh(0);
  const TriangleSurface s(base, up_normals(base));
  FeatureParams ridge, groove;
  ridge.radius = 0.12, ridge.height = 0.02, ridge.crease = -0.1;
  groove.radius = 0.08, groove.height = -0.015;
  const FeatureCurve A = curve_through(s, {Vec3(0.1, 0.2, 0), Vec3(0.5, 0.6, 0), Vec3(0.9, 0.5, 0)}, ridge);
  const FeatureCurve B = curve_through(s, {Vec3(0.2, 0.8, 0), Vec3(0.7, 0.15, 0)}, groove);
  const FeatureCurve C = curve_through(s, {Vec3(0.15, 0.5, 0), Vec3(0.85, 0.45, 0)}, ridge);
  ab.add(A), ab.add(B), ab.add(C);
  ba.add(C), ba.add(B);
  const int id = ba.add(A);
  const MatrixX3 original = ab.original().mesh(1).positions();
  CHECK((ab.result().mesh(1).positions() - original).norm() > 1e-3);
  CHECK((ab.result().mesh(1).positions() - ba.result().mesh(1).positions()).norm() < 1e-14);
  ba.remove(id);
  ba.add(A);
  CHECK((ab.result().mesh(1).positions() - ba.result().mesh(1).positions()).norm() < 1e-14);
  for (const auto& [fid, f] : std::map<int, FeatureCurve>(ba.features())) ba.remove(fid);
  CHECK((ba.result().mesh(1).positions() - original).norm() == 0.0);
}

TEST_CASE("feature application commutes with rigid motions, reference equals optimized", "[feature]") {
  const SurfaceMesh mushroom = read_mesh(test::data_path("mushroom.off"));
  const SurfaceMesh& m = mushroom;
  const Eigen::AngleAxisd rot(0.7, Vec3(1, 2, 3).normalized());
  const Vec3 shift(0.3, -1.2, 2.0);
  MatrixX3 moved = m.positions();
  for (Eigen::Index i = 0; i < moved.rows(); ++i) moved.row(i) = (rot * m.position(static_cast<int>(i)) + shift).transpose();
  SurfaceMesh m2 = m;
  m2.positions() = moved;

  FeaturedSurface f1(loop_hierarchy(m, 1), Backend::Optimized), f2(loop_hierarchy(m2, 1), Backend::Optimized);
  const SurfaceMesh& l1 = f1.original().mesh(1);
  const TriangleSurface s1(l1, loop_limit_normals(l1));
  const double diag = (l1.positions().colwise().maxCoeff() - l1.positions().colwise().minCoeff()).norm();
  // Two curves over the cap of the mushroom, drawn as surface points of level 1.
  const Vec3 top = l1.position(static_cast<int>([&] {
    Eigen::Index i;
    l1.positions().col(2).maxCoeff(&i);
    return i;
  }()));
  FeatureParams q;
  q.radius = 0.03 * diag;
  q.height = 0.004 * diag;
  std::vector<FeatureCurve> curves;
  for (const Vec3& dir : {Vec3(1, 0, 0), Vec3(0.3, 1, 0)}) {
    const Vec3 side = dir.normalized() * 0.06 * diag;
    MatrixX3 pts(3, 3);
    pts << (top - side).transpose(), (top + Vec3(0, 0, 0)).transpose(), (top + side).transpose();
    std::vector<SurfacePoint> sp = project_to_surface(s1, pts, 0.05 * diag, "curve");
    curves.push_back({"c", 1, sp, q});
  }
  for (const auto& c : curves) f1.add(c), f2.add(c);
  const MatrixX3 r1 = f1.result().mesh(1).positions(), r2 = f2.result().mesh(1).positions();
  double worst = 0;
  for (Eigen::Index i = 0; i < r1.rows(); ++i)
    worst = std::max(worst, (rot * Vec3(r1.row(i).transpose()) + shift - Vec3(r2.row(i).transpose())).norm());
  CHECK((r1 - f1.original().mesh(1).positions()).rowwise().norm().maxCoeff() > 0.5 * q.height);
  CHECK(worst < 1e-10 * diag);

  const TriangleSurface s(l1, loop_limit_normals(l1));
  std::vector<BaseCurve> base;
  for (const auto& c : curves) base.push_back(build_base_curve(s, c));
  const LevelPerturbation ref = compute_perturbation(s, base, Backend::Reference);
  const LevelPerturbation opt = compute_perturbation(s, base, Backend::Optimized);
  REQUIRE(ref.vertices == opt.vertices);
  CHECK((ref.displacement - opt.displacement).norm() == 0.0);
}

TEST_CASE("bad feature curves: off the surface, too few points, a radius beyond the flat scale", "[feature]") {
  const SurfaceMesh plane = plane_grid(8, 1.0);
  const TriangleSurface flat(plane, up_normals(plane));
  MatrixX3 off(2, 3);
  off << 0.2, 0.2, 0.0, 0.5, 0.5, 0.3;
  CHECK_THROWS_WITH(project_to_surface(flat, off, 0.01, "feature 'x'"),
                    Catch::Contains("point 1") && Catch::Contains("leaves the surface"));
  MatrixX3 outside(2, 3);
  outside << 0.5, 0.5, 0.0, 1.5, 0.5, 0.0;
  CHECK_THROWS_WITH(project_to_surface(flat, outside, 0.01, "feature 'x'"), Catch::Contains("leaves the surface"));
  FeatureCurve one{"single", 0, project_to_surface(flat, MatrixX3(Eigen::RowVector3d(0.5, 0.5, 0)), 1e-9, "p"), {}};
  CHECK_THROWS_WITH(build_base_curve(flat, one), Catch::Contains("at least 2 points"));
  FeatureCurve bad = one;
  bad.points.push_back(one.points[0]);
  bad.params.radius = -1;
  CHECK_THROWS_WITH(build_base_curve(flat, bad), Catch::Contains("radius") && Catch::Contains("> 0"));

  // A fold: the knot's coarse level is far from flat at the scale of a large radius.
  const SurfaceMesh knot = read_mesh(test::data_path("knot.off"));
  const TriangleSurface ks(knot, loop_limit_normals(knot));
  FeatureParams huge;
  huge.radius = 5.0 * ks.longest_edge() * 20;
  const FeatureCurve c{"wide", 0, {SurfacePoint{0, Vec3(0.3, 0.3, 0.4)}, SurfacePoint{10, Vec3(0.3, 0.3, 0.4)}}, huge};
  bool reported = false;
  try {
    const BaseCurve bc = build_base_curve(ks, c);
    const LevelPerturbation d = compute_perturbation(ks, {bc}, Backend::Optimized);
    CHECK(d.displacement.allFinite());
  } catch (const InvalidInput& e) {
    reported = std::string(e.what()).find("vertex") != std::string::npos ||
               std::string(e.what()).find("surface") != std::string::npos;
    INFO(e.what());
  }
  CHECK(reported);
}

TEST_CASE("adaptive Loop refinement: crack free, refines only near the features, stops when flat", "[feature]") {
  const SurfaceMesh mushroom = read_mesh(test::data_path("mushroom.off"));
  FeaturedSurface fs(loop_hierarchy(mushroom, 3), Backend::Optimized);
  const SurfaceMesh& l1 = fs.original().mesh(1);
  const TriangleSurface s1(l1, loop_limit_normals(l1));
  const double diag = (l1.positions().colwise().maxCoeff() - l1.positions().colwise().minCoeff()).norm();
  Eigen::Index top = 0;
  l1.positions().col(2).maxCoeff(&top);
  const Vec3 c = l1.position(static_cast<int>(top));
  MatrixX3 pts(2, 3);
  pts << (c - Vec3(0.05 * diag, 0, 0)).transpose(), (c + Vec3(0.05 * diag, 0, 0)).transpose();
  FeatureParams q;
  q.radius = 0.03 * diag;
  q.height = 0.01 * diag;
  fs.add({"ridge", 1, project_to_surface(s1, pts, 0.05 * diag, "ridge"), q});
  const MultiresSurface& r = fs.result();
  const AdaptiveMesh coarse = adaptive_mesh(r, 1, 20.0), fine = adaptive_mesh(r, 1, 2.0);
  // A T-junction would open a crack: a boundary loop the input does not have (it has one).
  CHECK(coarse.mesh.boundary_loops().size() == mushroom.boundary_loops().size());
  CHECK(fine.mesh.boundary_loops().size() == mushroom.boundary_loops().size());
  CHECK(fine.mesh.n_faces() > coarse.mesh.n_faces());
  CHECK(fine.mesh.n_faces() < r.mesh(3).n_faces());
  CHECK(coarse.triangles_per_level[3] < fine.triangles_per_level[3]);
  // The whole surface is kept: its area equals the finest level's within the flatness error.
  const auto area = [](const SurfaceMesh& m) {
    double a = 0;
    for (int f = 0; f < m.n_faces(); ++f) {
      const auto v = m.face_vertices(f);
      a += 0.5 * (m.position(v[1]) - m.position(v[0])).cross(m.position(v[2]) - m.position(v[0])).norm();
    }
    return a;
  };
  CHECK(area(fine.mesh) == Approx(area(r.mesh(3))).epsilon(0.01));
  CHECK_THROWS_WITH(adaptive_mesh(r, 1, 95.0), Catch::Contains("flatness_angle_deg"));
}
