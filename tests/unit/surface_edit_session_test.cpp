// Boier-Martin et al.'s edit as a session (design/surface_edit_session.h): driven step by step
// from C++ it gives the config run of the same steps bit for bit, a drag step reuses the prepared
// problem, and add / remove / move keep the session consistent.
#include <catch2/catch.hpp>

#include <yaml-cpp/yaml.h>

#include "fairshape/experiment/kinds/surface_edit/open_session.h"
#include "fairshape/experiment/kinds/surface_edit/run_one.h"
#include "fairshape/experiment/run_outputs.h"
#include "fairshape/io/mesh_io.h"
#include "test_support.h"

using namespace fairshape;

namespace {

// The cow's nose pulled on a Catmull-Clark level with §5's ladder (coarse level 0).
YAML::Node nose_pull(const std::string& extra) {
  return YAML::Load(R"(
name: session
seed: 1
implementation: optimized
input: {mesh: data/cow.off, representation: catmull-clark, levels: 1}
energy: [{type: detail_preserving, alpha: 0.1, beta: 1.0}]
constraints:
  - {type: fixed, region: {axis: x, from: 0.0, to: 0.3}}
  - {type: position, nearest: [0.5, 0.0, 0.0], offset: [0.06, 0.0, 0.032]}
problem: {constraint_mode: paper, accuracy: interactive, coarse_level: 0)" + extra + R"(}
output: {vtk: none, iterations: false}
)");
}

struct ConfigRun {
  MetricRow row;
  std::vector<std::vector<std::string>> steps;
  MatrixX3 final_positions;
};

ConfigRun run_config(const YAML::Node& cfg, const std::string& id) {
  const auto dir = test::scratch_dir("surface_session_" + id);
  create_run_folders(dir.string());
  SurfaceEditSpec spec = SurfaceEditSpec::from_config(cfg, components(), {test::source_path("")});
  RunCache cache;
  RunTables tables;
  const RunOutputs out{dir.string(), id, true, &tables};
  ConfigRun r;
  r.row = execute_run(spec, cache, out);
  const auto it = tables.rows().find("steps");
  if (it != tables.rows().end()) r.steps = it->second;
  r.final_positions = read_mesh(out.final_path()).positions();  // %.17g: every double exactly
  return r;
}

struct Opened {
  SurfaceEditSpec spec;
  std::shared_ptr<const MultiresSurface> rest;
  std::unique_ptr<SurfaceEditSession> session;
};

Opened open(const YAML::Node& cfg) {
  Opened o{SurfaceEditSpec::from_config(cfg, components(), {test::source_path("")}), nullptr, nullptr};
  RunCache cache;
  o.rest = std::make_shared<const MultiresSurface>(cache.hierarchy(o.spec));
  o.session = open_session(o.spec, o.rest);
  return o;
}

MatrixX3 finest(const SurfaceEditSession& s) { return s.current().mesh(s.current().levels()).positions(); }

}  // namespace

TEST_CASE("a session driven step by step equals the config run of the same steps, bit for bit",
          "[boier-martin][surface_session]") {
  // Two drag steps of the nose handle in the interactive mode, then the release in the converged mode.
  YAML::Node cfg = nose_pull("");
  cfg["steps"] = YAML::Load("[{offsets: {1: [0.03, 0.0, 0.016]}}, {offsets: {1: [0.06, 0.0, 0.032]}}, {accuracy: converged}]");
  const ConfigRun run = run_config(cfg, "schedule");
  INFO(run.row.at("message"));
  CHECK(run.row.at("termination") == "converged");
  REQUIRE(run.steps.size() == 3);
  CHECK(run.steps[0][2] == "interactive");
  CHECK(run.steps[2][2] == "converged");

  Opened o = open(cfg);
  SurfaceEditSession& s = *o.session;
  s.move(1, Vec3(0.03, 0.0, 0.016));
  const SurfaceEditStep first = s.solve();
  CHECK(first.accuracy == "interactive");
  CHECK(first.summary.succeeded());
  CHECK(first.orientation.folds.flipped.empty());
  CHECK(first.energy > 0);
  const int prepared = s.preparations();
  s.move(1, Vec3(0.06, 0.0, 0.032));
  (void)s.solve();
  CHECK(s.preparations() == prepared);  // a drag step: the interactive mode's factor reused
  const SurfaceEditStep release = s.solve(Accuracy::Converged);
  CHECK(release.accuracy == "converged");
  CHECK(release.constraint_residual < 1e-9);
  CHECK(finest(s) == run.final_positions);
}

TEST_CASE("problem.drag_steps is the schedule of scaled steps, and a session scaling its targets gives it",
          "[boier-martin][surface_session]") {
  const ConfigRun drag = run_config(nose_pull(", drag_steps: 2"), "drag");
  YAML::Node scheduled = nose_pull("");
  scheduled["steps"] = YAML::Load("[{scale: 0.5}, {scale: 1}]");
  const ConfigRun steps = run_config(scheduled, "scaled");
  CHECK(steps.final_positions == drag.final_positions);
  REQUIRE(drag.steps.size() == 2);
  CHECK(drag.steps[0][1] == "0.5");

  Opened o = open(nose_pull(", drag_steps: 2"));
  o.session->scale(0.5);
  (void)o.session->solve();
  o.session->scale(1.0);
  const SurfaceEditStep last = o.session->solve();
  CHECK(last.summary.succeeded());
  CHECK(finest(*o.session) == drag.final_positions);
}

TEST_CASE("a session's handles: numbered in order, moved, added and removed, conflicts refused",
          "[boier-martin][surface_session]") {
  YAML::Node cfg = nose_pull("");
  cfg["problem"] = YAML::Load("{constraint_mode: kkt}");
  Opened o = open(cfg);
  SurfaceEditSession& s = *o.session;
  CHECK(s.handles() == std::vector<int>{0, 1});
  (void)s.solve();
  const MatrixX3 before = finest(s);
  CHECK_THROWS_AS(s.move(2, Vec3::Zero()), InvalidInput);
  CHECK_THROWS_AS(s.solve(Accuracy::Interactive), InvalidInput);  // no ladder configured

  // A handle that holds a vertex the fixed region also holds cannot move it elsewhere.
  YAML::Node on_back = YAML::Load("{type: position, nearest: [-0.5, 0.0, 0.0], offset: [0, 0, 0]}");
  Config k(on_back, "added");
  SessionConstraint added{components().constraints.create("position", Backend::Optimized, k)};
  const int h = s.add(added);
  CHECK(h == 2);
  CHECK_THROWS_WITH(s.move(h, Vec3(0, 0.1, 0)), Catch::Contains("also held by"));
  s.remove(h);
  CHECK_THROWS_AS(s.move(h, Vec3::Zero()), InvalidInput);
  CHECK(s.add(added) == 3);  // a removed handle's number is not reused
  s.remove(3);
  const int prepared = s.preparations();
  const SurfaceEditStep again = s.solve();
  CHECK(s.preparations() == prepared + 1);  // the rows changed: prepared anew
  CHECK(again.summary.succeeded());
  CHECK(finest(s) == before);

  // A move and a move back: the targets and the surface of the configured edit again.
  s.move(1, Vec3(0.0, 0.05, 0.0));
  const SurfaceEditStep moved = s.solve();
  CHECK(moved.constraint_residual < 1e-9);
  CHECK((finest(s) - before).norm() > 1e-3);
  CHECK(s.preparations() == prepared + 1);  // a move reuses the factor
  s.move(1, Vec3(0.06, 0.0, 0.032));
  (void)s.solve();
  CHECK((finest(s) - before).cwiseAbs().maxCoeff() < 1e-12);
}
