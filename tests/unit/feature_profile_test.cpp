// The feature profile where it is seen: a curve drawn on any level l of a Loop
// hierarchy shows the requested height, width and cross-section on the finest level and on the
// limit surface, within the documented 2 % — on a plane, a sphere and the helmet. The paper's
// literal semantics (profile_on: drawn_level, the old behaviour) misses that on coarser levels,
// which the same measurement shows.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>

#include "fairshape/feature/feature_scale.h"
#include "fairshape/feature/featured_surface.h"
#include "fairshape/feature/profile_measure.h"
#include "fairshape/io/mesh_io.h"
#include "feature_test_meshes.h"
#include "test_support.h"

using namespace fairshape;
using namespace fairshape::feature;
using fairshape::test::cylinder;
using fairshape::test::plane_grid;

namespace {

// The icosahedron with every triangle split into `n`² and the vertices put on the unit sphere.
SurfaceMesh sphere(int n) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  const std::vector<Vec3> ico{{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                              {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  const int tri[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                          {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                          {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  std::vector<Vec3> points;
  std::map<std::tuple<long, long, long>, int> index;
  const auto vertex = [&](const Vec3& p) {
    const Vec3 q = p.normalized();
    const auto key = std::make_tuple(std::lround(q.x() * 1e9), std::lround(q.y() * 1e9), std::lround(q.z() * 1e9));
    const auto [it, added] = index.try_emplace(key, static_cast<int>(points.size()));
    if (added) points.push_back(q);
    return it->second;
  };
  PolygonList faces;
  for (const auto& f : tri) {
    const Vec3 a = ico[static_cast<std::size_t>(f[0])], b = ico[static_cast<std::size_t>(f[1])], c = ico[static_cast<std::size_t>(f[2])];
    const auto at = [&](int i, int j) { return vertex(a + (b - a) * i / n + (c - a) * j / n); };
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        faces.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        if (i + j + 1 < n) faces.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  }
  MatrixX3 V(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) V.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  return SurfaceMesh::from_polygons(V, faces);
}

MultiresSurface loop_hierarchy(const SurfaceMesh& base, int levels) {
  SubdivisionOptions opt;
  opt.scheme = SchemeType::Loop;
  return MultiresSurface(base, opt, levels, Backend::Optimized);
}

struct Case {
  std::string surface;
  SurfaceMesh base;
  int levels;
  std::vector<Vec3> points;  // near the surface: projected onto the drawn level
  FeatureParams params;
};

// One feature drawn on `level`, evaluated with `target`; its measure.
FeatureMeasure measured(const Case& c, int level, ProfileTarget target, Backend backend = Backend::Optimized) {
  FeaturedSurface fs(loop_hierarchy(c.base, c.levels), backend, target);
  const SurfaceMesh& drawn = fs.original().mesh(level);
  const TriangleSurface s(drawn, loop_limit_normals(drawn));
  MatrixX3 m(static_cast<Eigen::Index>(c.points.size()), 3);
  for (std::size_t i = 0; i < c.points.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = c.points[i].transpose();
  fs.add({"f", level, project_to_surface(s, m, 0.2, "test curve"), c.params});
  const std::vector<FeatureMeasure> all = measure_features(fs);
  REQUIRE(all.size() == 1);
  return all[0];
}

std::vector<Case> cases() {
  std::vector<Case> out;
  FeatureParams groove;
  groove.radius = 0.2, groove.height = -0.03;
  out.push_back({"plane", plane_grid(4, 1.0), 4, {Vec3(0.25, 0.45, 0), Vec3(0.5, 0.5, 0), Vec3(0.75, 0.55, 0)}, groove});
  // Left 1.5 times as wide as right, the height falling to half along the curve.
  FeatureParams ridge;
  ridge.radius = 0.45, ridge.left_right_ratio = 1.5, ridge.height = 0.04, ridge.end_height_ratio = 0.5;
  out.push_back({"sphere", sphere(6), 3, {Vec3(-0.3, 0.1, 1).normalized(), Vec3(0, 0, 1), Vec3(0.3, -0.1, 1).normalized()}, ridge});
  FeatureParams helmet;
  helmet.radius = 0.1, helmet.height = -0.02;
  out.push_back({"helmet", read_mesh(test::data_path("helmet.off")), 3,
                 {Vec3(-0.05, 0.0, 0.332), Vec3(0.06, 0.0026, 0.3437), Vec3(0.16, 0.0, 0.334)}, helmet});
  return out;
}

void check_within(const ProfileMeasure& m, const FeatureParams& q, const char* where) {
  INFO(where << ": height " << m.height_min << " .. " << m.height_max << " (requested " << q.height << "), height error "
             << m.height_error << ", widths " << m.width_left << " / " << m.width_right << " (r " << q.radius << " / "
             << q.right_radius() << "), profile error " << m.profile_error);
  CHECK(m.profile_error <= q.profile_tolerance);
  CHECK(m.height_error <= q.profile_tolerance);
  CHECK(m.width_error <= q.width_tolerance);
}

}  // namespace

TEST_CASE("a feature drawn on any level shows its profile on the finest level and the limit within 2 percent", "[feature][profile]") {
  for (const Case& c : cases())
    for (int level = 0; level <= c.levels; ++level) {
      INFO(c.surface << ", drawn on level " << level << " of " << c.levels);
      const FeatureMeasure m = measured(c, level, ProfileTarget::Limit);
      check_within(m.fine, c.params, "finest level");
      check_within(m.limit, c.params, "limit");
      CHECK(m.within_tolerance);
      // The limit is solved for: exact at the finest vertices up to the cut-off of the solve.
    CHECK(m.limit.profile_error < 0.25 * c.params.profile_tolerance);
    }
}

TEST_CASE("profile_on finest makes the finest control points exact, the limit within 2 percent", "[feature][profile]") {
  for (const Case& c : cases())
    for (int level : {0, c.levels - 1}) {
      INFO(c.surface << ", drawn on level " << level);
      const FeatureMeasure m = measured(c, level, ProfileTarget::Finest);
      CHECK(m.fine.profile_error < 1e-12);
      check_within(m.limit, c.params, "limit");
    }
}

TEST_CASE("the drawn level's control points alone (the paper read literally) miss the profile on coarser levels", "[feature][profile]") {
  // The measured failure of drawn-level profiles, kept as a property of profile_on: drawn_level: the same
  // measurement that passes above reports it, and it grows the coarser the drawn level.
  for (const Case& c : cases()) {
    INFO(c.surface);
    const FeatureMeasure coarse = measured(c, 0, ProfileTarget::DrawnLevel);
    const FeatureMeasure finer = measured(c, c.levels - 1, ProfileTarget::DrawnLevel);
    CHECK(!coarse.within_tolerance);
    CHECK(coarse.limit.profile_error > 5 * c.params.profile_tolerance);
    CHECK(coarse.limit.profile_error > finer.limit.profile_error);
  }
}

TEST_CASE("visible profile: reference and optimized back ends agree exactly", "[feature][profile]") {
  const Case c = cases()[2];
  FeaturedSurface ref(loop_hierarchy(c.base, 2), Backend::Reference), opt(loop_hierarchy(c.base, 2), Backend::Optimized);
  const SurfaceMesh& drawn = ref.original().mesh(1);
  const TriangleSurface s(drawn, loop_limit_normals(drawn));
  MatrixX3 m(3, 3);
  for (int i = 0; i < 3; ++i) m.row(i) = c.points[static_cast<std::size_t>(i)].transpose();
  const FeatureCurve curve{"f", 1, project_to_surface(s, m, 0.2, "test curve"), c.params};
  ref.add(curve), opt.add(curve);
  CHECK((ref.result().mesh(2).positions() - opt.result().mesh(2).positions()).norm() == 0.0);
  CHECK((ref.result().mesh(2).positions() - ref.original().mesh(2).positions()).norm() > 0.5 * std::abs(c.params.height));
}

namespace {

// The local scale (feature/feature_scale.h) of a feature on one surface drawn through `points`.
FeatureScale scale_of(const SurfaceMesh& mesh, const std::vector<Vec3>& points, double height) {
  const TriangleSurface s(mesh, loop_limit_normals(mesh));
  MatrixX3 m(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  FeatureParams q;
  q.radius = 0.1, q.height = height;
  return feature_scale(s, build_base_curve(s, {"f", 0, project_to_surface(s, m, 0.2, "test curve"), q}));
}

}  // namespace

TEST_CASE("a feature taller than the local scale of the surface is a miss that says which scale", "[feature][profile]") {
  const SurfaceMesh ball = loop_hierarchy(sphere(4), 2).mesh(2);
  const std::vector<Vec3> on_ball{Vec3(-0.3, 0.1, 1).normalized(), Vec3(0, 0, 1), Vec3(0.3, -0.1, 1).normalized()};
  // A groove into the unit sphere folds past its radius of curvature; a fine one does not.
  const FeatureScale deep = scale_of(ball, on_ball, -1.3);
  CHECK(deep.exceeded());
  CHECK(deep.limit == "curvature");
  CHECK(deep.scale == Approx(1.0).epsilon(0.15));
  CHECK_THAT(feature_scale_miss(deep), Catch::Contains("exceeds the local scale") && Catch::Contains("curvature"));
  CHECK_FALSE(scale_of(ball, on_ball, -0.05).exceeded());
  CHECK(feature_scale_miss(scale_of(ball, on_ball, -0.05)).empty());
  // A ridge on it bends away from the centre: only the sphere's size (2√3) bounds it.
  const FeatureScale tall = scale_of(ball, on_ball, 1.3);
  CHECK_FALSE(tall.exceeded());
  CHECK(tall.limit == "size");
  // On a flat patch of side 1 the size bounds any height.
  const std::vector<Vec3> on_plane{Vec3(0.25, 0.45, 0), Vec3(0.5, 0.5, 0), Vec3(0.75, 0.55, 0)};
  const FeatureScale flat = scale_of(plane_grid(8, 1.0), on_plane, 5.0);
  CHECK(flat.exceeded());
  CHECK(flat.limit == "size");
  CHECK(flat.scale == Approx(std::sqrt(2.0)).epsilon(1e-9));
  // Two parallel sheets 0.05 apart: a groove pushed towards the other reaches it.
  SurfaceMesh slab = plane_grid(8, 1.0), other = plane_grid(8, 1.0);
  other.positions().col(2).array() -= 0.05;
  MatrixX3 V(slab.n_vertices() + other.n_vertices(), 3);
  V << slab.positions(), other.positions();
  PolygonList faces = slab.polygons();
  for (auto f : other.polygons()) {
    for (int& v : f) v += slab.n_vertices();
    faces.push_back(f);
  }
  const FeatureScale through = scale_of(SurfaceMesh::from_polygons(V, faces), on_plane, -0.08);
  CHECK(through.exceeded());
  CHECK(through.limit == "thickness");
  CHECK(through.scale == Approx(0.05).epsilon(1e-6));
}

TEST_CASE("a run's features.csv marks a feature taller than the surface's scale, naming it", "[feature][profile]") {
  Case c = cases()[0];  // the plane of side 1
  c.params.height = -3.0;
  const FeatureMeasure m = measured(c, 2, ProfileTarget::Limit);
  CHECK_FALSE(m.within_tolerance);
  CHECK_THAT(m.why, Catch::Contains("exceeds the local scale"));
}

TEST_CASE("only the surface profile_on names decides a feature's verdict, the other is reported", "[feature][profile]") {
  // A groove 5 finest edges wide along a grid line of the plane, on the finest of 4 levels: the
  // finest control points and the limit differ by the Loop smoothing of the displacement, about
  // h (h_L / r)² — 4 % of h here, beyond the 2 % tolerance on whichever surface is not made exact.
  Case c = cases()[0];
  c.points = {Vec3(0.25, 0.5, 0), Vec3(0.5, 0.5, 0), Vec3(0.75, 0.5, 0)};
  c.params.radius = 5.0 / 64;
  c.params.quadratic = false;
  const FeatureMeasure limit = measured(c, 4, ProfileTarget::Limit);
  INFO("limit: finest profile error " << limit.fine.profile_error << ", limit " << limit.limit.profile_error << " " << limit.why);
  CHECK(limit.fine.profile_error > c.params.profile_tolerance);  // reported ...
  check_within(limit.limit, c.params, "limit");
  CHECK(limit.within_tolerance);  // ... but the limit, which profile_on names, decides
  CHECK(limit.why.empty());
  const FeatureMeasure finest = measured(c, 4, ProfileTarget::Finest);
  INFO("finest: limit profile error " << finest.limit.profile_error << " " << finest.why);
  CHECK(finest.limit.profile_error > c.params.profile_tolerance);
  check_within(finest.fine, c.params, "finest level");
  CHECK(finest.within_tolerance);
  // The paper's own semantics make neither surface exact: both decide, and the finest misses.
  const FeatureMeasure paper = measured(c, 4, ProfileTarget::DrawnLevel);
  CHECK_FALSE(paper.within_tolerance);
  CHECK_THAT(paper.why, Catch::Contains("limit") || Catch::Contains("finest level"));
  CHECK(profile_gates(ProfileTarget::Limit).limit);
  CHECK_FALSE(profile_gates(ProfileTarget::Limit).fine);
  CHECK(profile_gates(ProfileTarget::Finest).fine);
  CHECK_FALSE(profile_gates(ProfileTarget::Finest).limit);
}
