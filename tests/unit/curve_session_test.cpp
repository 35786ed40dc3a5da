// The curve editing loop a designer drives from a config (issue 25 part 6): a drag split into
// steps, each solved from the curve the previous one left, and the per-solve history.
#include <catch2/catch.hpp>

#include <yaml-cpp/yaml.h>

#include "experiment/kinds/curve/curve_run.h"
#include "experiment/run_outputs.h"
#include "test_support.h"

using namespace fairshape;

namespace {

struct CurveResult {
  MetricRow row;
  std::vector<std::vector<std::string>> steps, iterations;
};

CurveResult run_curve(const YAML::Node& cfg, const std::string& id) {
  const auto dir = test::scratch_dir("curve_session_" + id);
  create_run_folders(dir.string());
  CurveRunSpec spec = CurveRunSpec::from_config(cfg, {test::source_path("")});
  RunTables tables;
  CurveResult r;
  r.row = execute_curve_run(spec, RunOutputs{dir.string(), id, true, &tables});
  r.steps = tables.rows().at("steps");
  r.iterations = tables.rows().at("iterations");
  return r;
}

YAML::Node wave_edit(const std::string& moves) {
  return YAML::Load(R"(
name: drag
input: {curve: data/curves/wave129.obj}
edits: [{level: 0, moves: )" + moves + R"(}]
optimization:
  beta: 0.01
  solver: {type: trust_region, length_tolerance: 1.0e-12, max_solves: 5000}
output: {vtk: none, final_curve: false}
)");
}

}  // namespace

TEST_CASE("a drag in steps: equal shares of the move, one editing loop each, every one at a minimum", "[sauvage][curve_session]") {
  // Splitting: offsets divided, chord scales multiplying to the whole one (the chord grows by
  // equal amounts).
  YAML::Node by = wave_edit("[{index: -1, by: [-0.3, 0.1, 0]}, {index: 0, by: [0, 0.2, 0]}]");
  by["edits"][0]["drag_steps"] = 3;
  const CurveRunSpec spec = CurveRunSpec::from_config(by, {test::source_path("")});
  REQUIRE(spec.edits.size() == 3);
  Vec3 sum = Vec3::Zero();
  for (const CurveEdit& e : spec.edits) sum += e.moves[0].offset;
  CHECK((sum - Vec3(-0.3, 0.1, 0)).norm() < 1e-15);
  YAML::Node chord = wave_edit("[{index: -1, chord_scale: 0.7}]");
  chord["edits"][0]["drag_steps"] = 4;
  const CurveRunSpec cs = CurveRunSpec::from_config(chord, {test::source_path("")});
  double product = 1;
  for (const CurveEdit& e : cs.edits) product *= e.moves[0].chord_scale;
  CHECK(product == Approx(0.7).epsilon(1e-14));

  // Run: four loops, each converged at a local minimum (the run's second-order check is on the
  // last one), four stage rows each with its drag step, the per-solve history of every loop.
  const CurveResult r = run_curve(chord, "drag4");
  INFO(r.row.at("message"));
  CHECK(r.row.at("termination") == "converged");
  CHECK(r.row.at("edits") == "4");
  CHECK(std::stod(r.row.at("min_reduced_hessian_eig")) > 0);
  CHECK(std::stod(r.row.at("length_error_max")) < 1e-11);
  REQUIRE(r.steps.size() == 16);
  for (std::size_t k = 0; k < r.steps.size(); ++k) {
    CHECK(r.steps[k][0] == std::to_string(k / 4));
    CHECK(r.steps[k].back() == std::to_string(k / 4 + 1) + "/4");
  }
  // iterations.csv: edit, solve, length_error, stationarity, objective, seconds; every loop
  // has rows, solves count up within a loop, the last row of each meets the tolerances.
  int total = 0;
  for (int edit = 0; edit < 4; ++edit) {
    int last_solve = -1;
    std::vector<std::string> last;
    for (const auto& it : r.iterations)
      if (it[0] == std::to_string(edit)) {
        CHECK(std::stoi(it[1]) > last_solve);
        last_solve = std::stoi(it[1]);
        last = it;
      }
    REQUIRE(!last.empty());
    CHECK(std::stod(last[2]) <= 1e-12);
    CHECK(std::stod(last[3]) <= 1e-8);
    CHECK(std::isfinite(std::stod(last[4])));
    total += last_solve;
  }
  CHECK(std::to_string(total) == r.row.at("solves"));
  // A whole-move run differs (the problem is not convex; a drag follows the minimum it starts
  // from) but keeps the lengths as well.
  const CurveResult whole = run_curve(wave_edit("[{index: -1, chord_scale: 0.7}]"), "whole");
  CHECK(whole.row.at("termination") == "converged");
  CHECK(whole.steps.back().back() == "1/1");
}
