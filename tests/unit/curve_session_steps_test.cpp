// The curve session (curve_design/curve_session.h) driven step by step from C++ gives the
// config run of the same steps bit for bit, measures each step on its result, and refuses steps
// out of order without changing.
#include <catch2/catch.hpp>

#include <yaml-cpp/yaml.h>

#include "fairshape/core/error.h"
#include "fairshape/curve_design/curve_components.h"
#include "fairshape/curve_design/curve_session.h"
#include "fairshape/experiment/kinds/curve/curve_run.h"
#include "fairshape/experiment/run_outputs.h"
#include "fairshape/io/mesh_io.h"
#include "test_support.h"

using namespace fairshape;

namespace {

CurveMove move(int index, double x, double y) {
  CurveMove m;
  m.index = index;
  m.offset = Vec3(x, y, 0);
  return m;
}

// The settings of tests/data/configs/curve_session_steps.yaml, made from the registries as a C++ caller would.
CurveEditSettings settings() {
  const CurveComponents& cc = curve_components();
  Config none;
  CurveEditSettings s;
  s.beta = 0.1;
  s.smoothness = cc.energies.create("bending", Backend::Optimized, none);
  s.constraints.push_back(cc.constraints.create("segment_lengths", Backend::Optimized, none));
  Config solver(YAML::Load("{max_solves: 500, linearized: {linearization: newton}}"), "solver");
  s.solver = cc.solvers.create("linearized", Backend::Optimized, solver);
  return s;
}

}  // namespace

TEST_CASE("a curve session step by step gives the config run of the same steps bit for bit", "[sauvage][curve_session]") {
  const Polyline wave = read_polyline(test::source_path("data/curves/wave129.obj"));
  CurveSession session(wave, 7, settings());
  CurveEdit drag;
  drag.edit_level = 2;
  drag.wrinkle_level = 3;
  drag.moves = {move(4, -0.15, 0.05)};
  for (int k = 1; k <= 3; ++k) {
    const CurveStep s = session.drag_step(drag, 3);
    INFO("drag step " << k << ": " << s.summary.message);
    CHECK(s.index == k - 1);
    CHECK(s.drag_step == k);
    CHECK(s.summary.termination == Termination::Converged);
    CHECK(s.checks.metrics.length_error_max < 1e-8);  // the lengths of the curve the session started from
    CHECK(s.checks.out_of_plane < 1e-12);
    CHECK(s.checks.self_crossings == s.checks.original_self_crossings);
    CHECK((k < 3 ? s.checks.handle_reach == 1 : s.checks.handle_reach > 0.5));  // judged at the drag's end
    CHECK(s.curve() == session.current().points);
  }
  CurveEdit one;
  one.edit_level = 3;
  one.wrinkle_level = 4;
  one.moves = {move(8, -0.02, 0)};
  const CurveStep last = session.edit(one);
  INFO(last.summary.message);
  CHECK(last.index == 3);
  CHECK(last.succeeded());
  CHECK(last.check_s >= 0);
  CHECK(session.totals().steps == 4);

  const auto dir = test::scratch_dir("curve_session_steps");
  create_run_folders(dir.string());
  CurveRunSpec spec = CurveRunSpec::from_config(YAML::LoadFile(test::source_path("tests/data/configs/curve_session_steps.yaml")),
                                                {test::source_path("")});
  RunTables tables;
  const MetricRow row = execute_curve_run(spec, RunOutputs{dir.string(), "steps", true, &tables});
  const Polyline run = read_polyline((dir / "final.obj").string());  // %.17g: every double exactly
  CHECK(row.at("edits") == "4");
  CHECK(row.at("termination") == to_string(session.outcome().termination));
  CHECK(row.at("message") == session.outcome().message);
  CHECK(row.at("solves") == std::to_string(session.totals().solves));
  CHECK(run.points == session.current().points);
}

TEST_CASE("a curve session refuses steps out of order and is unchanged by a refused one", "[sauvage][curve_session]") {
  const Polyline wave = read_polyline(test::source_path("data/curves/wave129.obj"));
  CurveSession session(wave, 7, settings());
  CHECK(session.control_points(2) == 5);
  CHECK_THROWS_AS(session.control_points(8), InvalidInput);
  CurveEdit off;
  off.edit_level = 2;
  off.moves = {move(5, 0.1, 0)};
  CHECK_THROWS_WITH(session.edit(off), Catch::Contains("not on the level-e polygon"));
  CHECK(session.totals().steps == 0);
  CHECK(session.current().points == wave.points);
  CurveEdit drag;
  drag.edit_level = 3;
  drag.moves = {move(4, 0, 0.06)};
  (void)session.drag_step(drag, 2);
  CHECK_THROWS_WITH(session.edit(off), Catch::Contains("a drag of 2 steps is under way (1 taken)"));
  CurveEdit other = drag;
  other.moves[0].offset.y() = 0.07;
  CHECK_THROWS_WITH(session.drag_step(other, 2), Catch::Contains("take its remaining steps"));
  const CurveStep end = session.drag_step(drag, 2);
  CHECK(end.drag_step == 2);
  CHECK(session.totals().steps == 2);
  CHECK_THROWS_WITH(CurveSession(wave, 8, settings()), Catch::Contains("allows 0..7"));
}
