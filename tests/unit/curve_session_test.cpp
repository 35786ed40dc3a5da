// The curve editing loop a designer drives from a config: a drag split into
// steps, each solved from the curve the previous one left, and the per-solve history.
#include <catch2/catch.hpp>

#include <cmath>

#include <Eigen/Geometry>
#include <yaml-cpp/yaml.h>

#include "fairshape/experiment/kinds/curve/curve_run.h"
#include "fairshape/core/error.h"
#include "fairshape/experiment/run_outputs.h"
#include "fairshape/io/mesh_io.h"
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
  const auto table = [&](const std::string& name) {
    const auto it = tables.rows().find(name);
    return it == tables.rows().end() ? std::vector<std::vector<std::string>>{} : it->second;
  };
  r.steps = table("steps");
  r.iterations = table("iterations");
  return r;
}

YAML::Node wave_edit(const std::string& moves) {
  return YAML::Load(R"(
name: drag
input: {curve: data/curves/wave129.obj}
edits: [{level: 0, moves: )" + moves + R"(}]
editing: {explicit_step: sweep, details: global, solve_region: curve}  # as measured for part 6 (README)
optimization:
  beta: 0.01
  constraints: [{type: segment_lengths}]
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

TEST_CASE("the projection baseline: meets lengths only as its weight grows, and never says converged short of them",
          "[sauvage][curve_session]") {
  // Figure 1's edit at three penalty weights: the length error falls with the weight and stays
  // above the tolerance, so each run ends with the error it reached, not `converged`.
  double previous = INFINITY;
  for (const double weight : {1e2, 1e4, 1e6}) {
    YAML::Node cfg = wave_edit("[{index: -1, chord_scale: 0.7}]");
    cfg["optimization"]["solver"]["type"] = "projection";
    cfg["optimization"]["solver"]["projection"]["weight"] = weight;
    const CurveResult r = run_curve(cfg, "projection" + std::to_string(static_cast<int>(std::log10(weight))));
    INFO(weight << ": " << r.row.at("message"));
    CHECK(r.row.at("termination") != "converged");
    CHECK(r.row.at("message").find("length error") != std::string::npos);
    const double error = std::stod(r.row.at("length_error_max"));
    CHECK(error > 1e-12);
    CHECK(error < previous);
    previous = error;
    CHECK(std::isnan(std::stod(r.iterations.front()[3])));  // stationarity: measured on the last iterate only
    CHECK(std::isfinite(std::stod(r.iterations.back()[3])));
  }
  // An attractor of the right lengths at β = 1 is the answer: met at the first iteration.
  YAML::Node still = wave_edit("[{index: 1, by: [0, 0, 0]}]");
  still["optimization"]["beta"] = 1.0;
  still["optimization"]["solver"]["type"] = "projection";
  const CurveResult r = run_curve(still, "projection_still");
  INFO(r.row.at("message"));
  CHECK(r.row.at("termination") == "converged");
  CHECK(r.row.at("solves") == "1");
}

TEST_CASE("tangent and position constraints on any point: held to the tolerance at a minimum, bad ones refused",
          "[sauvage][curve_session]") {
  const auto angle = [](const MatrixX3& X, int a, int b, const MatrixX3& R) {
    const Vec3 d = (X.row(b) - X.row(a)).transpose(), t = (R.row(b) - R.row(a)).transpose();
    return std::atan2(d.cross(t).norm(), d.dot(t));
  };
  const Polyline wave = read_polyline(test::data_path("curves/wave129.obj"));
  // Figure 1's edit with both end tangents kept as they were and the middle point kept where
  // it was: every one met, the lengths too, at a point the trust region judges a minimum.
  YAML::Node cfg = wave_edit("[{index: -1, chord_scale: 0.7}]");
  cfg["optimization"]["constraints"].push_back(YAML::Load("{type: tangent, points: endpoints, direction: reference}"));
  cfg["optimization"]["constraints"].push_back(YAML::Load("{type: pin, points: [64], at: reference}"));
  cfg["output"]["final_curve"] = true;
  const CurveResult r = run_curve(cfg, "tangents");
  INFO(r.row.at("message"));
  REQUIRE(r.row.at("termination") == "converged");
  CHECK(std::stod(r.row.at("min_reduced_hessian_eig")) >= 0);
  CHECK(std::stod(r.row.at("length_error_max")) < 1e-11);
  const Polyline held = read_polyline((test::scratch_path("curve_session_tangents") / "final.obj").string());
  CHECK(angle(held.points, 0, 1, wave.points) < 1e-9);
  CHECK(angle(held.points, 127, 128, wave.points) < 1e-9);
  CHECK((held.points.row(64) - wave.points.row(64)).norm() < 1e-9);
  // Without them the ends turn and the middle moves: the constraints did something.
  YAML::Node free_cfg = wave_edit("[{index: -1, chord_scale: 0.7}]");
  free_cfg["output"]["final_curve"] = true;
  REQUIRE(run_curve(free_cfg, "tangents_free").row.at("termination") == "converged");
  const Polyline free_curve = read_polyline((test::scratch_path("curve_session_tangents_free") / "final.obj").string());
  CHECK(angle(free_curve.points, 127, 128, wave.points) > 0.1);
  CHECK((free_curve.points.row(64) - wave.points.row(64)).norm() > 0.1);
  // The projection baseline projects lengths and pins only: it says so.
  cfg["optimization"]["solver"]["type"] = "projection";
  const CurveResult p = run_curve(cfg, "tangents_projection");
  CHECK(p.row.at("termination") == "invalid_input");
  CHECK(p.row.at("message").find("segment lengths and pins only") != std::string::npos);

  // Bad input: a point off the curve, a zero direction, an unknown `at`.
  const auto refused = [&](const std::string& constraint, const std::string& says) {
    YAML::Node bad = wave_edit("[{index: -1, chord_scale: 0.7}]");
    bad["optimization"]["constraints"].push_back(YAML::Load(constraint));
    INFO(constraint);
    try {
      CurveRunSpec spec = CurveRunSpec::from_config(bad, {test::source_path("")});
      const CurveResult out = run_curve(bad, "refused");
      CHECK(out.row.at("termination") == "invalid_input");
      CHECK(out.row.at("message").find(says) != std::string::npos);
    } catch (const InvalidConfig& e) {
      CHECK(std::string(e.what()).find(says) != std::string::npos);
    }
  };
  refused("{type: tangent, points: [500]}", "point 500 is not on the curve (0..128)");
  refused("{type: tangent, points: [3], direction: [0, 0, 0]}", "direction: expected a nonzero [x, y, z]");
  refused("{type: pin, points: [3], at: final}", "'final'");
}
