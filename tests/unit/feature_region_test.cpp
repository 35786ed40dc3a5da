// Region-limited re-evaluation between design steps (FeaturedSurface::set_region_evaluation,
// featured_surface_region.cpp): a session of steps — a coarse feature moved, a
// fine one re-parameterized, a feature added on a level that had none, features removed until
// none is left, one added again — evaluated once region by region and once whole after every
// step, on the patch, the helmet and the helmet with random local details. Every level agrees to
// 1e-12 (of the model's size), every vertex outside the reported region is bit for bit what it
// was before the step, and a small change recomputes a small part.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <functional>

#include "fairshape/feature/featured_surface.h"
#include "fairshape/feature/profile_measure.h"
#include "fairshape/io/mesh_io.h"
#include "test_support.h"

using namespace fairshape;
using namespace fairshape::feature;

namespace {

MultiresSurface loop_hierarchy(const SurfaceMesh& base, int levels) {
  SubdivisionOptions opt;
  opt.scheme = SchemeType::Loop;
  return MultiresSurface(base, opt, levels, Backend::Optimized);
}

double diagonal(const SurfaceMesh& m) {
  return (m.positions().colwise().maxCoeff() - m.positions().colwise().minCoeff()).norm();
}

// A feature through world points near `level` of `h` (projected there).
FeatureCurve curve_on(const MultiresSurface& h, int level, std::vector<Vec3> points, double radius, double height,
                      const std::string& name) {
  const SurfaceMesh& m = h.mesh(level);
  const TriangleSurface s(m, loop_limit_normals(m));
  MatrixX3 X(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) X.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  FeatureParams q;
  q.radius = radius;
  q.height = height;
  return {name, level, project_to_surface(s, X, 0.1, name), q};
}

struct Model {
  std::string name;
  SurfaceMesh base;
  int levels;
  // Features: a wide one on level 1, a fine one on the finest level crossing it, one added later
  // on level 2 (far from both), the wide one moved.
  std::vector<Vec3> wide, wide_moved, fine, later;
  double wide_r, fine_r, later_r;
  bool details = false;  // random local details on every finer level (a remeshed surface's kind)
};

std::vector<Model> models() {
  return {{"patch", read_mesh(test::data_path("ks_patch.off")), 3,
           {Vec3(-0.6, -0.2, 0), Vec3(0.6, 0.1, 0)}, {Vec3(-0.6, -0.1, 0), Vec3(0.6, 0.2, 0)},
           {Vec3(0.0, -0.6, 0), Vec3(0.1, 0.6, 0)}, {Vec3(0.75, -0.85, 0), Vec3(0.9, -0.6, 0)}, 0.3, 0.1, 0.15},
          {"helmet", read_mesh(test::data_path("helmet.off")), 3,
           {Vec3(-0.05, 0.0, 0.332), Vec3(0.16, 0.0, 0.334)}, {Vec3(-0.05, 0.02, 0.332), Vec3(0.16, 0.02, 0.334)},
           {Vec3(0.05, -0.09, 0.33), Vec3(0.06, 0.08, 0.33)}, {Vec3(-0.2, -0.07, 0.215), Vec3(-0.18, 0.03, 0.245)}, 0.06, 0.03, 0.04}};
}

// The hierarchy of a model, with small random details in local frames when it asks for them.
MultiresSurface hierarchy_of(const Model& m) {
  MultiresSurface h = loop_hierarchy(m.base, m.levels);
  if (!m.details) return h;
  std::srand(7);
  for (int k = 1; k <= m.levels; ++k) {
    const double size = 1e-3 * std::ldexp(1.0, -k);
    h.set_details(k, size * MatrixX3::Random(h.mesh(k).n_vertices(), 3), DetailSpace::Local);
  }
  h.synthesize(DetailSpace::Local);
  return h;
}

// Max difference of two hierarchies over every level.
double largest_difference(const MultiresSurface& a, const MultiresSurface& b) {
  double worst = 0;
  for (int k = 0; k <= a.levels(); ++k)
    worst = std::max(worst, (a.mesh(k).positions() - b.mesh(k).positions()).cwiseAbs().maxCoeff());
  return worst;
}

// Vertices outside the reported region that changed at all (bit for bit).
long long changed_outside(const MultiresSurface& before, const MultiresSurface& after, const EvaluationReport& r) {
  long long n = 0;
  for (int k = 0; k <= after.levels(); ++k) {
    std::vector<char> in(static_cast<std::size_t>(after.mesh(k).n_vertices()), 0);
    for (int v : r.vertices[static_cast<std::size_t>(k)]) in[static_cast<std::size_t>(v)] = 1;
    for (int v = 0; v < after.mesh(k).n_vertices(); ++v)
      if (!in[static_cast<std::size_t>(v)] && (after.mesh(k).positions().row(v).array() != before.mesh(k).positions().row(v).array()).any())
        ++n;
  }
  return n;
}

long long total_vertices(const MultiresSurface& h) {
  long long n = 0;
  for (int k = 0; k <= h.levels(); ++k) n += h.mesh(k).n_vertices();
  return n;
}

}  // namespace

TEST_CASE("a design step re-evaluated on its region equals the whole re-evaluation", "[feature][steps]") {
  std::vector<Model> all = models();
  all.push_back(all.back());
  all.back().name = "helmet with details";
  all.back().details = true;
  for (const Model& model : all) {
    for (const ProfileTarget target : {ProfileTarget::Limit, ProfileTarget::Finest, ProfileTarget::DrawnLevel}) {
      if (model.name != "patch" && target != ProfileTarget::Limit) continue;  // the patch covers the other targets
      INFO(model.name << ", profile_on " << profile_target_names().name(target));
      const MultiresSurface plain = hierarchy_of(model);
      const double tol = 1e-12 * diagonal(model.base);
      const int L = model.levels;
      FeaturedSurface region(plain, Backend::Optimized, target), whole(plain, Backend::Optimized, target);
      whole.set_region_evaluation(false);
      // The reference back end's region evaluation against the optimized whole one (the patch,
      // the paper's drawn-level profile: the reference perturbation scans every vertex).
      const bool with_reference = model.name == "patch" && target == ProfileTarget::DrawnLevel;
      FeaturedSurface reference(plain, Backend::Reference, target);
      const FeatureCurve wide = curve_on(plain, 1, model.wide, model.wide_r, 0.15 * model.wide_r, "wide");
      const FeatureCurve fine = curve_on(plain, L, model.fine, model.fine_r, -0.3 * model.fine_r, "fine");
      const FeatureCurve later = curve_on(plain, 2, model.later, model.later_r, 0.15 * model.later_r, "later");
      FeatureCurve wide_moved = curve_on(plain, 1, model.wide_moved, model.wide_r, 0.15 * model.wide_r, "wide");
      FeatureCurve fine_higher = fine;
      fine_higher.params.height *= 1.5;
      int w = -1, f = -1, l = -1;
      const std::vector<std::pair<std::string, std::function<void(FeaturedSurface&)>>> steps{
          {"start", [&](FeaturedSurface& s) { w = s.add(wide), f = s.add(fine); }},
          {"the wide feature moved", [&](FeaturedSurface& s) { s.replace(w, wide_moved); }},
          {"the fine one higher", [&](FeaturedSurface& s) { s.replace(f, fine_higher); }},
          {"a feature on level 2", [&](FeaturedSurface& s) { l = s.add(later); }},
          {"the wide and the level-2 ones removed", [&](FeaturedSurface& s) { s.remove(w), s.remove(l); }},
          {"the last one removed", [&](FeaturedSurface& s) { s.remove(f); }},
          {"the fine one again", [&](FeaturedSurface& s) { f = s.add(fine); }}};
      MultiresSurface before = plain;
      for (std::size_t k = 0; k < steps.size(); ++k) {
        INFO("step " << k << ": " << steps[k].first);
        steps[k].second(region);
        steps[k].second(whole);
        if (with_reference) {
          steps[k].second(reference);
          CHECK(largest_difference(reference.result(), whole.result()) <= tol);
          CHECK(reference.last_evaluation().region == (k > 0));
        }
        const MultiresSurface& r = region.result();
        const MultiresSurface& u = whole.result();
        CHECK(largest_difference(r, u) <= tol);
        const EvaluationReport& report = region.last_evaluation();
        CHECK(report.region == (k > 0));
        CHECK_FALSE(whole.last_evaluation().region);
        if (k > 0) {
          CHECK(changed_outside(before, r, report) == 0);
          // A feature added away from the others recomputes a small part of the hierarchy (one
          // that crosses another re-solves the limit fit of both: one block of equations).
          INFO("recomputed " << report.vertices_recomputed << " of " << total_vertices(r));
          if (k == 3) CHECK(report.vertices_recomputed < total_vertices(r) / 8);
          CHECK(report.vertices_recomputed > 0);
        }
        before = r;
      }
      // What is measured is the same too.
      const std::vector<FeatureMeasure> a = measure_features(region), b = measure_features(whole);
      REQUIRE(a.size() == b.size());
      for (std::size_t i = 0; i < a.size(); ++i) {
        CHECK(std::abs(a[i].limit.profile_error - b[i].limit.profile_error) <= 1e-12);
        CHECK(std::abs(a[i].fine.height_max - b[i].fine.height_max) <= 1e-12);
      }
    }
  }
}
