// FeatureSession (feature/feature_session.h), Khodakovsky & Schröder's editing session, driven step
// by step from C++ against the config run of the same design steps (run_feature_steps, the run
// kind's loop: a groove moved, a ridge raised and a feature added in one step, a ridge removed):
// every level bit for bit, steps.csv's counts the same. And what each step measures on its own
// result: the placement against what was asked, the vertices it moved, folds, a refused drawing
// changing nothing.
#include <catch2/catch.hpp>

#include <yaml-cpp/yaml.h>

#include "fairshape/experiment/kinds/feature/feature_run.h"
#include "fairshape/experiment/kinds/feature/feature_steps.h"
#include "fairshape/feature/feature_session.h"
#include "test_support.h"

using namespace fairshape;

namespace {

// The patch at 3 levels with the design steps of tests/cli/feature_run.sh's stepped session.
YAML::Node stepped_config() {
  return YAML::Load("name: steps\n"
                    "input: {mesh: " + test::data_path("ks_patch.off") + ", levels: 3}\n"
                    "feature_defaults: {radius: 0.18, height: 0.05, quadratic: true, profile_tolerance: 0.5, width_tolerance: 0.5}\n"
                    "adaptive: {enabled: false}\n"
                    "features:\n"
                    "  - {name: ridge_a, level: 2, until: 3, points: [[-0.8, -0.55, 0.0587], [-0.2, 0.1, 0.0042], [0.4, 0.25, 0.0155], [0.8, 0.7, 0.0474]]}\n"
                    "  - {name: ridge_b, level: 2, changes: [{step: 2, height: 0.1}], points: [[-0.75, 0.6, 0.0459], [0.0, 0.35, -0.0073], [0.7, -0.6, 0.0372]]}\n"
                    "  - {name: groove, level: 2, height: -0.04, radius: 0.12, moves: [{step: 1, by: [0, -0.2, 0]}], points: [[-0.6, -0.1, 0.0426], [0.1, -0.45, -0.0109], [0.75, 0.05, 0.0674]]}\n"
                    "  - {name: late, level: 2, step: 2, height: -0.03, radius: 0.1, points: [[-0.5, 0.8, -0.0084], [0.5, 0.8, -0.0084]]}\n");
}

bool same_bits(const MultiresSurface& a, const MultiresSurface& b) {
  if (a.levels() != b.levels()) return false;
  for (int k = 0; k <= a.levels(); ++k)
    if (a.mesh(k).positions().rows() != b.mesh(k).positions().rows() ||
        !(a.mesh(k).positions().array() == b.mesh(k).positions().array()).all())
      return false;
  return true;
}

}  // namespace

TEST_CASE("a feature session driven step by step ends on the config run's surface, bit for bit", "[feature][session]") {
  // The config run: the run kind's own set-up and step loop.
  FeatureRunSpec run_spec = FeatureRunSpec::from_config(stepped_config(), {});
  RunTables tables;
  const RunOutputs out{test::scratch_dir("steps").string(), "steps", true, &tables};
  OpenedFeatureSession run = open_feature_session(run_spec);
  (void)run_feature_steps(run_spec, *run.session, out);
  const std::vector<std::vector<std::string>>& rows = tables.rows().at("steps");
  REQUIRE(rows.size() == 4);

  // The same steps by hand.
  const FeatureRunSpec spec = FeatureRunSpec::from_config(stepped_config(), {});
  FeatureSession session(feature_hierarchy(spec), feature_session_options(spec));
  const auto drawing = [&](int k) { return feature::FeatureDrawing(spec.features[static_cast<std::size_t>(k)]); };
  const int ridge_a = session.stage_add(drawing(0)), ridge_b = session.stage_add(drawing(1)), groove = session.stage_add(drawing(2));
  std::vector<FeatureStep> steps;
  steps.push_back(session.evaluate());
  feature::FeatureDrawing moved = drawing(2);
  for (Vec3& p : moved.world_points) p += Vec3(0, -0.2, 0);
  steps.push_back(session.replace(groove, moved));
  feature::FeatureParams raised = session.features().at(ridge_b).params;
  raised.height = 0.1;
  steps.push_back(session.apply({FeatureEdit::set_params(ridge_b, raised), FeatureEdit::add(drawing(3))}));
  steps.push_back(session.remove(ridge_a));

  CHECK(same_bits(session.surface(), run.session->surface()));
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const FeatureStep& s = steps[i];
    INFO("step " << i);
    CHECK(rows[i][6] == (i == 0 ? std::string() : std::to_string(s.vertices_changed)));  // vertices_changed
    CHECK(rows[i][7] == (s.evaluation.region ? "region" : "whole"));
    CHECK(rows[i][9] == std::to_string(s.evaluation.vertices_recomputed));
    CHECK(s.summary.termination == Termination::Converged);
    CHECK(s.folds.flipped.empty());
    CHECK(s.surface == &session.surface());
    CHECK(s.solve_s > 0);
  }
  // The first step placed the three features; each later one its own drawing.
  REQUIRE(steps[0].placed.size() == 3);
  CHECK(steps[0].added == std::vector<int>{ridge_a, ridge_b, groove});
  CHECK(steps[0].vertices_changed == -1);
  CHECK(steps[1].moved == std::vector<int>{groove});
  REQUIRE(steps[1].placed.size() == 1);
  // Where the groove was placed against where it was asked: the points lie off the surface by
  // their z rounding, within what placing accepts.
  CHECK(steps[1].placed[0].farthest > 0);
  CHECK(steps[1].placed[0].farthest < steps[1].placed[0].allowed);
  CHECK(steps[2].changed == std::vector<int>{ridge_b});
  CHECK(steps[2].added.size() == 1);
  CHECK(steps[3].removed == std::vector<int>{ridge_a});
  // Later steps recompute a region: no more than they changed, less than the whole hierarchy.
  for (std::size_t i = 1; i < steps.size(); ++i) {
    CHECK(steps[i].evaluation.region);
    CHECK(steps[i].vertices_changed > 0);
    CHECK(steps[i].vertices_changed <= steps[i].evaluation.vertices_recomputed);
    CHECK(steps[i].evaluation.vertices_recomputed < steps[0].evaluation.vertices_recomputed);
    CHECK(steps[i].max_change > 0);
  }
  CHECK(session.features().size() == 3);
  // A step with nothing to apply recomputes and moves nothing.
  const FeatureStep idle = session.evaluate();
  CHECK(idle.evaluation.vertices_recomputed == 0);
  CHECK(idle.vertices_changed == 0);
  CHECK(same_bits(session.surface(), run.session->surface()));
}

TEST_CASE("a feature session refuses what it cannot place and changes nothing, and measures folds and profiles",
          "[feature][session]") {
  const FeatureRunSpec spec = FeatureRunSpec::from_config(stepped_config(), {});
  FeatureSession session(feature_hierarchy(spec), feature_session_options(spec));
  const int ridge = session.stage_add(feature::FeatureDrawing(spec.features[1]));
  const FeatureStep first = session.evaluate(FeatureChecks::Profiles);
  REQUIRE(first.profiles);
  CHECK(first.profiles->features.size() == 1);
  CHECK(first.summary.termination == first.profiles->summary.termination);
  const MultiresSurface before = session.surface();

  // A drawing off the surface, an unknown id, a side narrower than two finest edges: refused
  // before anything changes (the next step is still a region step).
  feature::FeatureDrawing off(spec.features[1]);
  for (Vec3& p : off.world_points) p.z() += 5;
  CHECK_THROWS_AS(session.replace(ridge, off), InvalidInput);
  CHECK_THROWS_AS(session.remove(ridge + 7), InvalidInput);
  feature::FeatureParams narrow = session.features().at(ridge).params;
  narrow.radius = 0.01;
  CHECK_THROWS_WITH(session.set_params(ridge, narrow), Catch::Contains("narrower than 2 edges"));
  CHECK(same_bits(session.surface(), before));
  CHECK(session.features().at(ridge).params.radius == spec.features[1].curve.params.radius);

  // Far too tall for the patch: the step says it folded, where.
  feature::FeatureParams tall = session.features().at(ridge).params;
  tall.height = 5.0;
  const FeatureStep folded = session.set_params(ridge, tall);
  CHECK(folded.evaluation.region);
  CHECK(folded.summary.termination == Termination::Folded);
  CHECK_THAT(folded.summary.message, Catch::Contains("faces flipped"));
  CHECK(session.measure().summary.termination == Termination::Folded);
  // Back to its height: the same surface as before, bit for bit outside the region and to
  // rounding inside it.
  const FeatureStep back = session.set_params(ridge, spec.features[1].curve.params);
  CHECK(back.summary.termination == Termination::Converged);
  const MatrixX3& now = session.surface().mesh(3).positions();
  CHECK((now - before.mesh(3).positions()).cwiseAbs().maxCoeff() < 1e-12);
}
