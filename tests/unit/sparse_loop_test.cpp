// Truly adaptive evaluation (feature/adaptive_evaluation.h, feature/sparse_loop.h): the sparse
// levels are the uniform hierarchy's vertices and faces exactly (plain and with features drawn on
// a coarse and on the finest level), the refined region is local, the output is crack free on
// closed models, and each feature's own flatness threshold holds inside its support.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "fairshape/feature/adaptive_evaluation.h"
#include "fairshape/feature/featured_surface.h"
#include "fairshape/feature/profile_measure.h"
#include "fairshape/feature/sparse_measure.h"
#include "feature_test_checks.h"
#include "feature_test_meshes.h"
#include "fairshape/io/mesh_io.h"
#include "test_support.h"

using namespace fairshape;
using namespace fairshape::feature;

namespace {

using test::check_same_measure;
using test::diagonal;
using test::loop_options;

// A feature through two points of `level` of `h` (projected there). The helmet's crown between
// x = −0.05 and 0.16 is where feature_profile_test draws its curves too.
FeatureCurve feature_between(const MultiresSurface& h, int level, const Vec3& a, const Vec3& b, double radius,
                             double height, double angle_deg, const std::string& name) {
  const SurfaceMesh& m = h.mesh(level);
  const TriangleSurface s(m, loop_limit_normals(m));
  MatrixX3 pts(2, 3);
  pts << a.transpose(), b.transpose();
  FeatureParams q;
  q.radius = radius;
  q.height = height;
  q.flatness_angle_deg = angle_deg;
  return {name, level, project_to_surface(s, pts, 0.05, name), q};
}

// Every sparse level against the uniform one: counts, face half-edges and corners, positions.
void check_against_uniform(const AdaptiveEvaluation& a, const MultiresSurface& u, double tolerance) {
  REQUIRE(static_cast<int>(a.levels.size()) == u.levels() + 1);
  for (int k = 0; k <= u.levels(); ++k) {
    const SparseLevel& s = a.levels[k];
    const SurfaceMesh& m = u.mesh(k);
    INFO("level " << k);
    CHECK(s.n_vertices == m.n_vertices());
    CHECK(s.n_edges == m.n_edges());
    CHECK(s.n_faces == m.n_faces());
    int wrong_faces = 0;
    for (int f = 0; f < s.n_local_faces(); ++f) {
      int h = m.face_halfedge(static_cast<int>(s.face[f]));
      for (int i = 0; i < 3; ++i, h = m.next(h))
        wrong_faces += s.halfedges[f][i] != h || s.vertex[s.corners[f][i]] != m.from_vertex(h);
    }
    CHECK(wrong_faces == 0);
    double worst = 0;
    for (int v = 0; v < s.n_local_vertices(); ++v)
      worst = std::max(worst, (s.positions.row(v) - m.positions().row(static_cast<int>(s.vertex[v]))).norm());
    CHECK(worst <= tolerance);
  }
}

// Crack free: no boundary loop, the Euler characteristic of the input, every vertex where the
// uniform level it was taken from has it.
void check_crack_free(const AdaptiveEvaluation& a, const MultiresSurface& u, const SurfaceMesh& base, double tolerance) {
  CHECK(a.mesh.boundary_loops().size() == base.boundary_loops().size());
  const auto euler = [](const SurfaceMesh& m) { return m.n_vertices() - m.n_edges() + m.n_faces(); };
  CHECK(euler(a.mesh) == euler(base));
  double worst = 0;
  for (int v = 0; v < a.mesh.n_vertices(); ++v)
    worst = std::max(worst, (a.mesh.position(v) - u.mesh(a.mesh_vertex_level[v]).position(static_cast<int>(a.mesh_vertex[v])))
                                .norm());
  CHECK(worst <= tolerance);
}

}  // namespace

TEST_CASE("sparse Loop levels equal the uniform hierarchy on every kept vertex", "[feature][sparse]") {
  const SurfaceMesh helmet = read_mesh(test::data_path("helmet.off"));
  const int L = 3;
  const MultiresSurface u(helmet, loop_options(), L, Backend::Optimized);
  AdaptiveEvaluationOptions o;
  o.surface_angle_deg = 4;
  const AdaptiveEvaluation a = evaluate_adaptive(helmet, loop_options(), L, {}, o);
  const double tol = 1e-12 * diagonal(helmet);
  check_against_uniform(a, u, tol);
  check_crack_free(a, u, helmet, tol);
  // Flat enough somewhere, curved elsewhere: neither nothing nor everything refined.
  CHECK(a.levels[L].n_local_faces() > 0);
  CHECK(a.levels[L].n_local_faces() < u.mesh(L).n_faces());
  CHECK(a.mesh.n_faces() < u.mesh(L).n_faces());
  // from_level = L with no threshold is the uniform mesh.
  o.surface_angle_deg = 0;
  o.from_level = L;
  const AdaptiveEvaluation whole = evaluate_adaptive(helmet, loop_options(), L, {}, o);
  CHECK(whole.mesh.n_faces() == u.mesh(L).n_faces());
  CHECK(whole.mesh.n_vertices() == u.mesh(L).n_vertices());
}

TEST_CASE("sparse Loop levels on a mesh with a boundary, and bad input", "[feature][sparse]") {
  const SurfaceMesh patch = read_mesh(test::data_path("ks_patch.off"));
  const int L = 3;
  const MultiresSurface u(patch, loop_options(), L, Backend::Optimized);
  AdaptiveEvaluationOptions o;
  o.surface_angle_deg = 1;
  const AdaptiveEvaluation a = evaluate_adaptive(patch, loop_options(), L, {}, o);
  check_against_uniform(a, u, 1e-12 * diagonal(patch));
  check_crack_free(a, u, patch, 1e-12 * diagonal(patch));
  CHECK(a.mesh.n_faces() < u.mesh(L).n_faces());
  o.from_level = 4;
  CHECK_THROWS_WITH(evaluate_adaptive(patch, loop_options(), L, {}, o), Catch::Contains("from_level 4 outside 0..3"));
  o.from_level = 0;
  o.surface_angle_deg = 90;
  CHECK_THROWS_WITH(evaluate_adaptive(patch, loop_options(), L, {}, o), Catch::Contains("surface_angle_deg"));
  SubdivisionOptions cc;
  CHECK_THROWS_WITH(evaluate_adaptive(patch, cc, L, {}, {}), Catch::Contains("Loop"));
  SurfaceMesh creased = patch;
  creased.set_edge_sharpness(creased.from_vertex(0), creased.to_vertex(0), 2.0);
  CHECK_THROWS_WITH(evaluate_adaptive(creased, loop_options(), L, {}, {}), Catch::Contains("crease"));
  FeatureCurve deep{"deep", L + 1, {}, {}};
  CHECK_THROWS_WITH(evaluate_adaptive(patch, loop_options(), L, {deep}, {}), Catch::Contains("feature 'deep': level 4"));
}

TEST_CASE("sparse Loop levels with features equal the uniform evaluation (drawn-level profile)", "[feature][sparse]") {
  const SurfaceMesh helmet = read_mesh(test::data_path("helmet.off"));
  const int L = 3;
  const MultiresSurface plain(helmet, loop_options(), L, Backend::Optimized);
  const double diag = diagonal(helmet);
  for (const auto& [level, backend] : {std::pair{1, Backend::Optimized}, std::pair{L, Backend::Optimized},
                                       std::pair{2, Backend::Reference}}) {
    INFO("feature drawn on level " << level << ", " << to_string(backend));
    const FeatureCurve c =
        feature_between(plain, level, Vec3(-0.05, 0.0, 0.332), Vec3(0.06, 0.0026, 0.3437), 0.04, -0.008, 3.0, "groove");
    FeaturedSurface fs(plain, backend, ProfileTarget::DrawnLevel);
    fs.add(c);
    const MultiresSurface& u = fs.result();
    AdaptiveEvaluationOptions o;
    o.backend = backend;
    const AdaptiveEvaluation e = evaluate_adaptive(helmet, loop_options(), L, {c}, o);
    CHECK(e.vertices_moved == static_cast<int>(fs.perturbation(level).vertices.size()));
    CHECK(e.vertices_moved > 0);
    check_against_uniform(e, u, 1e-12 * diag);
    check_crack_free(e, u, helmet, 1e-12 * diag);
  }
}

TEST_CASE("a small finest-level feature refines a small part of the surface", "[feature][sparse]") {
  const SurfaceMesh helmet = read_mesh(test::data_path("helmet.off"));
  const int L = 4;
  const MultiresSurface plain(helmet, loop_options(), L, Backend::Optimized);
  const FeatureCurve c =
      feature_between(plain, L, Vec3(0.0, 0.0, 0.335), Vec3(0.06, 0.0026, 0.3437), 0.01, 0.002, 2.0, "ridge");
  const AdaptiveEvaluation e = evaluate_adaptive(helmet, loop_options(), L, {c}, {});
  const double refined = double(e.levels[L].n_local_faces()) / plain.mesh(L).n_faces();
  INFO("finest faces computed: " << e.levels[L].n_local_faces() << " of " << plain.mesh(L).n_faces());
  CHECK(refined > 0);
  CHECK(refined < 0.05);
  CHECK(e.faces_computed() < plain.mesh(L).n_faces() / 10);
  CHECK(e.mesh.boundary_loops().empty());
  CHECK(e.vertices_moved > 0);
}

// A feature drawn below the finest level changes every finer level around it, and its profile is
// made exact and measured on the finest one (sparse_visible_profile.h): its neighbourhood is
// computed down to the finest level whatever its own flatness threshold (0.5° or 20° here), so no
// coarser leaf lies near it; where leaves are coarser, the threshold holds.
TEST_CASE("a coarse feature's neighbourhood is computed to the finest level, whatever its threshold", "[feature][sparse]") {
  const SurfaceMesh helmet = read_mesh(test::data_path("helmet.off"));
  const int L = 4;
  const MultiresSurface plain(helmet, loop_options(), L, Backend::Optimized);
  const double diag = diagonal(helmet);
  std::vector<FeatureCurve> features{
      feature_between(plain, 1, Vec3(-0.05, 0.0, 0.332), Vec3(0.0, 0.0, 0.335), 0.03, 0.01, 0.5, "fine"),
      feature_between(plain, 1, Vec3(0.11, 0.0, 0.336), Vec3(0.16, 0.0, 0.334), 0.03, 0.01, 20.0, "coarse")};
  FeaturedSurface fs(plain, Backend::Optimized, ProfileTarget::DrawnLevel);
  for (const auto& f : features) fs.add(f);
  const MultiresSurface& u = fs.result();
  const AdaptiveEvaluation e = evaluate_adaptive(helmet, loop_options(), L, features, {});
  check_against_uniform(e, u, 1e-12 * diag);
  check_crack_free(e, u, helmet, 1e-12 * diag);
  // Leaves (coarser than L) within half a radius of a feature's control polygon on level 1:
  // every edge midpoint of the next level lies within the feature's angle of the leaf's plane.
  const auto angle_at = [&](int k, int F) {
    const SurfaceMesh& m = u.mesh(k);
    double worst = 0;
    int h = m.face_halfedge(F);
    for (int i = 0; i < 3; ++i, h = m.next(h)) {
      const Vec3 a = m.position(m.from_vertex(h)), b = m.position(m.to_vertex(h)), o = m.position(m.to_vertex(m.next(h)));
      const Vec3 mid = u.mesh(k + 1).position(m.n_vertices() + SurfaceMesh::edge(h));
      const Vec3 n = (b - a).cross(o - a).normalized();
      worst = std::max(worst, std::asin(std::min(1.0, std::abs((mid - o).dot(n)) / (mid - o).norm())));
    }
    return worst * 180 / std::numbers::pi;
  };
  std::vector<int> leaves_near(2, 0), finest_near(2, 0);
  for (std::size_t i = 0; i < features.size(); ++i) {
    const TriangleSurface s1(u.mesh(1), loop_limit_normals(u.mesh(1)));
    const Vec3 a = s1.point(features[i].points[0]), b = s1.point(features[i].points[1]);
    const double r = features[i].params.radius;
    double worst = 0;
    for (int k = 1; k <= L; ++k) {
      const SparseLevel& S = e.levels[k];
      for (int f = 0; f < S.n_local_faces(); ++f) {
        if (e.split[k][f]) continue;
        const Vec3 c = (S.positions.row(S.corners[f][0]) + S.positions.row(S.corners[f][1]) +
                        S.positions.row(S.corners[f][2])).transpose() / 3;
        const Vec3 ab = b - a;
        const double t = std::clamp((c - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
        if ((c - (a + t * ab)).norm() > 0.5 * r) continue;
        if (k == L) { ++finest_near[i]; continue; }
        ++leaves_near[i];
        worst = std::max(worst, angle_at(k, static_cast<int>(S.face[f])));
      }
    }
    INFO(features[i].name << ": " << leaves_near[i] << " coarser leaves, " << finest_near[i] << " finest, worst angle "
                          << worst);
    CHECK(worst <= features[i].params.flatness_angle_deg);
  }
  for (int i : {0, 1}) {
    CHECK(leaves_near[static_cast<std::size_t>(i)] == 0);
    CHECK(finest_near[static_cast<std::size_t>(i)] > 0);
  }
}

TEST_CASE("sparse Loop levels on the knot and the cow, flatness everywhere", "[feature][sparse]") {
  for (const char* name : {"knot.off", "cow.off"}) {
    INFO(name);
    const SurfaceMesh m = read_mesh(test::data_path(name));
    const int L = 3;
    const MultiresSurface u(m, loop_options(), L, Backend::Optimized);
    AdaptiveEvaluationOptions o;
    o.surface_angle_deg = 3;
    o.from_level = 1;
    const AdaptiveEvaluation a = evaluate_adaptive(m, loop_options(), L, {}, o);
    check_against_uniform(a, u, 1e-12 * diagonal(m));
    check_crack_free(a, u, m, 1e-12 * diagonal(m));
    CHECK(a.mesh.n_faces() < u.mesh(L).n_faces());
    // With a ridge on level 2 from base vertex 0 to a vertex two edges away, both together.
    const int v1 = m.to_vertex(m.halfedge(0));
    int v2 = v1;
    for (int w : m.vertex_neighbors(v1))
      if ((m.position(w) - m.position(0)).norm() > (m.position(v2) - m.position(0)).norm()) v2 = w;
    double edge = 0;
    for (int e = 0; e < m.n_edges(); ++e) edge += (m.position(m.from_vertex(2 * e)) - m.position(m.to_vertex(2 * e))).norm();
    edge /= m.n_edges();
    const FeatureCurve c = feature_between(u, 2, m.position(0), m.position(v2), 0.5 * edge, 0.1 * edge, 1.0, "ridge");
    FeaturedSurface fs(u, Backend::Optimized, ProfileTarget::DrawnLevel);
    fs.add(c);
    const AdaptiveEvaluation b = evaluate_adaptive(m, loop_options(), L, {c}, o);
    CHECK(b.vertices_moved == static_cast<int>(fs.perturbation(2).vertices.size()));
    check_against_uniform(b, fs.result(), 1e-12 * diagonal(m));
    check_crack_free(b, fs.result(), m, 1e-12 * diagonal(m));
  }
}

TEST_CASE("a sparse evaluation measures its features as the uniform one, finest level and limit", "[feature][sparse][profile]") {
  struct Case {
    const char* name;
    SurfaceMesh base;
    int levels;
    Vec3 a, b;
    double radius, height;
  };
  const std::vector<Case> cases{
      {"helmet", read_mesh(test::data_path("helmet.off")), 3, Vec3(-0.05, 0.0, 0.332), Vec3(0.06, 0.0026, 0.3437), 0.04, -0.008},
      {"plane", test::plane_grid(6, 1.0), 3, Vec3(0.3, 0.45, 0), Vec3(0.7, 0.55, 0), 0.12, 0.03}};
  for (const Case& k : cases) {
    INFO(k.name);
    const MultiresSurface plain(k.base, loop_options(), k.levels, Backend::Optimized);
    const FeatureCurve c = feature_between(plain, k.levels, k.a, k.b, k.radius, k.height, 3.0, "f");
    FeaturedSurface uniform(plain, Backend::Optimized, ProfileTarget::DrawnLevel);
    uniform.add(c);
    const std::vector<FeatureMeasure> u = measure_features(uniform);
    const AdaptiveEvaluation e = evaluate_adaptive(k.base, loop_options(), k.levels, {c}, {});
    const std::vector<SparseFeatureMeasure> s = measure_sparse_features(e, k.levels, loop_options(), Backend::Optimized);
    REQUIRE(u.size() == 1);
    REQUIRE(s.size() == 1);
    // The sparse level is smaller than the uniform one, and the measure is not trivial.
    CHECK(e.levels[k.levels].n_local_vertices() < plain.mesh(k.levels).n_vertices());
    CHECK(std::abs(u[0].limit.height_max) > 0.5 * std::abs(k.height));
    INFO(s[0].limit_note);
    REQUIRE(s[0].limit_measured);
    CHECK(s[0].limit_note.empty());
    check_same_measure(s[0].fine, u[0].fine, 1e-10, "finest level");
    check_same_measure(s[0].limit, u[0].limit, 1e-10, "limit");

    // A vertex next to the curve without its one-ring: the limit is not measured, and said so.
    AdaptiveEvaluation cut = e;
    SparseLevel& S = cut.levels[static_cast<std::size_t>(k.levels)];
    const Vec3 mid = 0.5 * (e.curves[0].segments.front().a + e.curves[0].segments.back().b);
    int nearest = 0;
    for (int v = 1; v < S.n_local_vertices(); ++v)
      if ((cut.unperturbed[k.levels].row(v).transpose() - mid).norm() < (cut.unperturbed[k.levels].row(nearest).transpose() - mid).norm())
        nearest = v;
    S.complete[static_cast<std::size_t>(nearest)] = 0;
    const std::vector<SparseFeatureMeasure> partial = measure_sparse_features(cut, k.levels, loop_options(), Backend::Optimized);
    CHECK_FALSE(partial[0].limit_measured);
    CHECK_THAT(partial[0].limit_note, Catch::Contains("limit not measured") && Catch::Contains("one-ring"));
  }
}
