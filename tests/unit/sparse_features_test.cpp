// Features drawn below the finest level on a sparse Loop hierarchy (Khodakovsky &
// Schröder, "Fine level feature editing for subdivision surfaces", §2.5): whatever level a
// feature is drawn on and wherever its profile is made exact (profile_on), the sparse
// evaluation equals the uniform one (FeaturedSurface) on every vertex it computes, computes
// every finest vertex the features change, measures every feature as the uniform run does, is
// crack free on a closed model, and computes a region, not the whole surface.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "fairshape/feature/adaptive_evaluation.h"
#include "fairshape/feature/featured_surface.h"
#include "fairshape/feature/profile_measure.h"
#include "fairshape/feature/sparse_measure.h"
#include "fairshape/io/mesh_io.h"
#include "feature_test_checks.h"
#include "feature_test_meshes.h"
#include "test_support.h"

using namespace fairshape;
using namespace fairshape::feature;

namespace {

using test::check_same_measure;
using test::diagonal;
using test::loop_options;

struct Model {
  const char* name;
  SurfaceMesh base;
  int levels;
  std::vector<Vec3> points;  // near the surface, projected on the drawn level
  double radius, height;
};

std::vector<Model> models() {
  std::vector<Model> out;
  // The helmet (closed, genus 3): the crown, where feature_profile_test draws on every level.
  out.push_back({"helmet", read_mesh(test::data_path("helmet.off")), 3,
                 {Vec3(-0.05, 0.0, 0.332), Vec3(0.06, 0.0026, 0.3437), Vec3(0.16, 0.0, 0.334)}, 0.1, -0.02});
  // The open patch z = 0.12 (x² − ½y²) on [−1, 1]² (12 × 12 cells): a ridge across its middle,
  // its region reaching towards the boundary.
  const auto z = [](double x, double y) { return 0.12 * (x * x - 0.5 * y * y); };
  out.push_back({"patch", read_mesh(test::data_path("ks_patch.off")), 3,
                 {Vec3(-0.5, -0.2, z(-0.5, -0.2)), Vec3(0.1, 0.1, z(0.1, 0.1)), Vec3(0.5, 0.3, z(0.5, 0.3))}, 0.3, 0.05});
  return out;
}

FeatureCurve feature_on(const MultiresSurface& h, int level, const Model& m) {
  const SurfaceMesh& mesh = h.mesh(level);
  const TriangleSurface s(mesh, loop_limit_normals(mesh));
  MatrixX3 pts(static_cast<Eigen::Index>(m.points.size()), 3);
  for (std::size_t i = 0; i < m.points.size(); ++i) pts.row(static_cast<Eigen::Index>(i)) = m.points[i].transpose();
  FeatureParams q;
  q.radius = m.radius;
  q.height = m.height;
  return {"f", level, project_to_surface(s, pts, 0.05 * diagonal(mesh), "f"), q};
}

// Every kept vertex of every sparse level where the uniform result has it.
double worst_position(const AdaptiveEvaluation& a, const MultiresSurface& u) {
  double worst = 0;
  for (int k = 0; k <= u.levels(); ++k) {
    const SparseLevel& s = a.levels[static_cast<std::size_t>(k)];
    for (int v = 0; v < s.n_local_vertices(); ++v)
      worst = std::max(worst, (s.positions.row(v) - u.mesh(k).positions().row(static_cast<int>(s.vertex[v]))).norm());
  }
  return worst;
}

// Finest vertices the features change in the uniform result that the sparse level lacks.
int changed_but_absent(const AdaptiveEvaluation& a, const MultiresSurface& result, const MultiresSurface& plain) {
  const int L = plain.levels();
  const SparseLevel& s = a.levels[static_cast<std::size_t>(L)];
  int n = 0;
  for (int v = 0; v < plain.mesh(L).n_vertices(); ++v)
    if ((result.mesh(L).positions().row(v) - plain.mesh(L).positions().row(v)).squaredNorm() > 0 && s.vertex_of(v) < 0) ++n;
  return n;
}

void check_crack_free(const AdaptiveEvaluation& a, const SurfaceMesh& base) {
  CHECK(a.mesh.boundary_loops().size() == base.boundary_loops().size());
  const auto euler = [](const SurfaceMesh& m) { return m.n_vertices() - m.n_edges() + m.n_faces(); };
  CHECK(euler(a.mesh) == euler(base));
}

}  // namespace

TEST_CASE("features drawn on any level: sparse equals uniform, positions and measures", "[feature][sparse][profile]") {
  for (const Model& m : models()) {
    const MultiresSurface plain(m.base, loop_options(), m.levels, Backend::Optimized);
    const double tol = 1e-12 * diagonal(m.base);
    for (int level = 0; level <= m.levels; ++level) {
      const FeatureCurve c = feature_on(plain, level, m);
      for (const ProfileTarget target : {ProfileTarget::Limit, ProfileTarget::Finest, ProfileTarget::DrawnLevel}) {
        // The reference back end once per model (the coarsest feature, the default target).
        const Backend backend = level == 0 && target == ProfileTarget::Limit ? Backend::Reference : Backend::Optimized;
        INFO(m.name << ", drawn on level " << level << " of " << m.levels << ", profile_on "
                    << profile_target_names().name(target) << ", " << to_string(backend));
        FeaturedSurface uniform(plain, backend, target);
        uniform.add(c);
        const MultiresSurface& u = uniform.result();
        AdaptiveEvaluationOptions o;
        o.backend = backend;
        o.target = target;
        const AdaptiveEvaluation e = evaluate_adaptive(m.base, loop_options(), m.levels, {c}, o);
        CHECK(worst_position(e, u) <= tol);
        CHECK(changed_but_absent(e, u, plain) == 0);
        const std::vector<FeatureMeasure> mu = measure_features(uniform);
        const std::vector<SparseFeatureMeasure> ms = measure_sparse_features(e, m.levels, loop_options(), backend);
        REQUIRE(mu.size() == 1);
        REQUIRE(ms.size() == 1);
        INFO(ms[0].limit_note);
        REQUIRE(ms[0].limit_measured);
        check_same_measure(ms[0].fine, mu[0].fine, 1e-10, "finest level");
        check_same_measure(ms[0].limit, mu[0].limit, 1e-10, "limit");
        // Not trivial: the feature is seen at the limit, and only its region is computed.
        CHECK(std::abs(mu[0].limit.height_max) > 0.5 * std::abs(m.height));
        CHECK(e.levels[static_cast<std::size_t>(m.levels)].n_local_faces() < plain.mesh(m.levels).n_faces());
        if (m.base.boundary_loops().empty()) check_crack_free(e, m.base);
      }
    }
  }
}

TEST_CASE("features on two levels and a finest one, composed as the uniform run composes them", "[feature][sparse][profile]") {
  const Model helmet = models()[0];
  const MultiresSurface plain(helmet.base, loop_options(), helmet.levels, Backend::Optimized);
  Model across = helmet;
  across.points = {Vec3(0.06, -0.08, 0.33), Vec3(0.06, 0.08, 0.33)};
  across.radius = 0.04, across.height = 0.01;
  Model fine = helmet;
  fine.points = {Vec3(-0.04, 0.02, 0.333), Vec3(0.12, 0.02, 0.336)};
  fine.radius = 0.02, fine.height = 0.004;
  const std::vector<FeatureCurve> features{feature_on(plain, 1, helmet), feature_on(plain, 2, across),
                                           feature_on(plain, 3, fine)};
  for (const ProfileTarget target : {ProfileTarget::Limit, ProfileTarget::Finest}) {
    INFO("profile_on " << profile_target_names().name(target));
    FeaturedSurface uniform(plain, Backend::Optimized, target);
    for (const FeatureCurve& c : features) uniform.add(c);
    AdaptiveEvaluationOptions o;
    o.target = target;
    const AdaptiveEvaluation e = evaluate_adaptive(helmet.base, loop_options(), helmet.levels, features, o);
    CHECK(worst_position(e, uniform.result()) <= 1e-12 * diagonal(helmet.base));
    CHECK(changed_but_absent(e, uniform.result(), plain) == 0);
    const std::vector<FeatureMeasure> mu = measure_features(uniform);
    const std::vector<SparseFeatureMeasure> ms = measure_sparse_features(e, helmet.levels, loop_options(), Backend::Optimized);
    REQUIRE(ms.size() == mu.size());
    for (std::size_t i = 0; i < mu.size(); ++i) {
      INFO("feature drawn on level " << features[i].level << ": " << ms[i].limit_note);
      REQUIRE(ms[i].limit_measured);
      check_same_measure(ms[i].fine, mu[i].fine, 1e-10, "finest level");
      check_same_measure(ms[i].limit, mu[i].limit, 1e-10, "limit");
    }
    check_crack_free(e, helmet.base);
  }
}

TEST_CASE("a coarse feature computes its region, not the whole surface", "[feature][sparse]") {
  // Homer-like locality on the cow (5,804 faces) refined 4 times: a short ridge drawn on level 1.
  const SurfaceMesh cow = read_mesh(test::data_path("cow.off"));
  const int L = 4;
  const MultiresSurface plain(cow, loop_options(), 1, Backend::Optimized);
  const int v0 = 0, v1 = cow.to_vertex(cow.halfedge(0));
  double edge = 0;
  for (int e = 0; e < cow.n_edges(); ++e) edge += (cow.position(cow.from_vertex(2 * e)) - cow.position(cow.to_vertex(2 * e))).norm();
  edge /= cow.n_edges();
  Model m{"cow", cow, L, {cow.position(v0), cow.position(v1)}, edge, 0.2 * edge};
  const FeatureCurve c = feature_on(plain, 1, m);
  AdaptiveEvaluationOptions o;
  o.target = ProfileTarget::Limit;
  const AdaptiveEvaluation e = evaluate_adaptive(cow, loop_options(), L, {c}, o);
  const long long uniform_faces = static_cast<long long>(cow.n_faces()) << (2 * L);
  const int finest = e.levels[static_cast<std::size_t>(L)].n_local_faces();
  INFO("finest faces computed: " << finest << " of " << uniform_faces << ", all levels " << e.faces_computed() << ", passes "
                                 << e.passes);
  CHECK(finest > 0);
  CHECK(finest < uniform_faces / 50);
  CHECK(e.faces_computed() < uniform_faces / 20);
  check_crack_free(e, cow);
  const std::vector<SparseFeatureMeasure> ms = measure_sparse_features(e, L, loop_options(), Backend::Optimized);
  REQUIRE(ms.size() == 1);
  CHECK(ms[0].limit_measured);
}

TEST_CASE("features below the finest level on the knot, the cow, the open mushroom and the fandisk", "[feature][sparse][profile]") {
  // Models the sparse evaluation was not tuned on: a ridge between two base vertices two edges
  // apart, 0.6 mean base edges wide, drawn on levels 0..L − 1 (both back ends on level 1).
  struct Case {
    const char* file;
    int levels;
  };
  for (const Case& k : {Case{"knot.off", 3}, Case{"cow.off", 3}, Case{"mushroom.off", 3}, Case{"fandisk.off", 2}}) {
    const SurfaceMesh m = read_mesh(test::data_path(k.file));
    const MultiresSurface plain(m, loop_options(), k.levels, Backend::Optimized);
    // The flattest vertex away from the boundary (its neighbours' faces closest to one plane:
    // the fandisk has sharp edges, where no feature of this width fits), and a vertex two edges
    // from it. Not at the boundary: there the limit point of a boundary vertex lies on the
    // boundary, where the features' displacement jumps (a ray leaving the surface) — the uniform
    // evaluation itself changes by the whole displacement under a 1e-16 change of the point
    // (measured on the mushroom), so no two evaluations agree there beyond that.
    const auto normal = [&](int f) {
      const std::vector<int> c = m.face_vertices(f);
      return Vec3((m.position(c[1]) - m.position(c[0])).cross(m.position(c[2]) - m.position(c[0])).normalized());
    };
    int v0 = 0;
    double flattest = -2;
    for (int v = 0; v < m.n_vertices(); ++v) {
      bool near_boundary = m.is_boundary_vertex(v);
      for (int w : m.vertex_neighbors(v))
        for (int x : m.vertex_neighbors(w)) near_boundary = near_boundary || m.is_boundary_vertex(x);
      if (near_boundary) continue;
      const Vec3 n = normal(m.vertex_faces(v).front());
      double worst = 1;
      for (int w : m.vertex_neighbors(v))
        for (int f : m.vertex_faces(w)) worst = std::min(worst, normal(f).dot(n));
      if (worst > flattest) flattest = worst, v0 = v;
    }
    const int v1 = m.vertex_neighbors(v0).front();
    int v2 = v1;
    for (int w : m.vertex_neighbors(v1))
      if ((m.position(w) - m.position(v0)).norm() > (m.position(v2) - m.position(v0)).norm()) v2 = w;
    double edge = 0;
    for (int e = 0; e < m.n_edges(); ++e) edge += (m.position(m.from_vertex(2 * e)) - m.position(m.to_vertex(2 * e))).norm();
    edge /= m.n_edges();
    const Model model{k.file, m, k.levels, {m.position(v0), m.position(v2)}, 0.6 * edge, 0.1 * edge};
    for (int level = 0; level < k.levels; ++level)
      for (const Backend backend : {Backend::Optimized, Backend::Reference}) {
        if (backend == Backend::Reference && level != 1) continue;
        INFO(k.file << ", drawn on level " << level << " of " << k.levels << ", " << to_string(backend));
        const FeatureCurve c = feature_on(plain, level, model);
        FeaturedSurface uniform(plain, backend, ProfileTarget::Limit);
        uniform.add(c);
        AdaptiveEvaluationOptions o;
        o.backend = backend;
        o.target = ProfileTarget::Limit;
        const AdaptiveEvaluation e = evaluate_adaptive(m, loop_options(), k.levels, {c}, o);
        CHECK(worst_position(e, uniform.result()) <= 1e-12 * diagonal(m));
        CHECK(changed_but_absent(e, uniform.result(), plain) == 0);
        const std::vector<FeatureMeasure> mu = measure_features(uniform);
        const std::vector<SparseFeatureMeasure> ms = measure_sparse_features(e, k.levels, loop_options(), backend);
        REQUIRE(ms.size() == 1);
        INFO(ms[0].limit_note);
        REQUIRE(ms[0].limit_measured);
        check_same_measure(ms[0].fine, mu[0].fine, 1e-10, "finest level");
        check_same_measure(ms[0].limit, mu[0].limit, 1e-10, "limit");
        CHECK(e.levels[static_cast<std::size_t>(k.levels)].n_local_faces() < plain.mesh(k.levels).n_faces() / 4);
        if (m.boundary_loops().empty()) check_crack_free(e, m);
      }
  }
}

