// Welch & Witkin's modelling session in a config (§5): a point dragged over steps, a constraint
// removed, the current shape installed as the rest shape and melted again.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include <yaml-cpp/yaml.h>

#include "fairshape/experiment/kinds/sheet/sheet_run.h"
#include "fairshape/experiment/run_outputs.h"
#include "sheet_test_support.h"

using namespace fairshape;
using Catch::Matchers::Contains;

namespace {

const std::string kSession = std::string(R"(
name: session
sheets: [{name: s, spans: [8, 8], size: [2, 2]}]
energy: {alpha: 0.01, beta: 1}
output: {vtk: none}
constraints:)") + test::kCornerPinsYaml + R"(
  - {type: point, uv: [1, 1], by: [0, 0, 0.3], moves: [{step: 1, by: [0, 0, 0.2]}]}
  - {type: point, uv: [0.5, 1.5], by: [0, 0, -0.2], until: 2}
actions:
  - {step: 3, do: install_rest_shape}
  - {step: 4, do: melt_rest_shape}
)";
// Steps: 0 the design, 1 the point dragged 0.2 higher, 2 the second point removed, 3 the shape
// installed as rest (nothing else changes), 4 the rest shape melted.

std::vector<std::vector<std::string>> run_steps(const YAML::Node& cfg, const std::string& id, MetricRow& row) {
  return test::run_sheet_steps(cfg, std::string("sheet_session_") + id, id, row);
}

}  // namespace

TEST_CASE("a sheet session: a dragged point, a removed constraint, a rest shape installed and melted", "[sheet][session]") {
  const YAML::Node cfg = YAML::Load(kSession);
  MetricRow row;
  const auto steps = run_steps(cfg, "all", row);
  INFO(row.at("message"));
  REQUIRE(row.at("termination") == "converged");
  REQUIRE(steps.size() == 5);
  const auto energy = [&](int k) { return std::stod(steps[static_cast<std::size_t>(k)][8]); };
  const auto rows = [&](int k) { return std::stoi(steps[static_cast<std::size_t>(k)][4]); };
  for (int k = 0; k < 5; ++k) CHECK(std::stod(steps[static_cast<std::size_t>(k)][7]) <= 1e-9);  // every point met, dragged or not
  CHECK(energy(1) > energy(0));  // dragged higher
  CHECK(rows(2) == rows(1) - 1);  // the second point removed
  CHECK(energy(2) < energy(1));
  // Installed with the constraints unchanged: the current shape is the minimizer of eq. 6
  // about itself, energy 0.
  CHECK(energy(3) == Approx(0).margin(1e-9 * energy(2)));
  // Melted: eq. 4 again, with step 2's constraints: step 2's answer.
  CHECK(energy(4) == Approx(energy(2)).epsilon(1e-9));
}

TEST_CASE("session keys are checked: a removal before the start, a move not after it, an unknown sheet", "[sheet][session]") {
  const auto refused = [](const std::string& path, const std::string& value) {
    YAML::Node cfg = YAML::Load(kSession);
    if (path == "until") cfg["constraints"][5]["until"] = YAML::Load(value);
    if (path == "move") cfg["constraints"][4]["moves"][0]["step"] = YAML::Load(value);
    if (path == "sheet") cfg["actions"][0]["sheet"] = YAML::Load(value);
    return SheetRunSpec::from_config(cfg);
  };
  CHECK_THROWS_WITH(refused("until", "0"), Contains("constraints[5].until: 0 must come after step 0"));
  CHECK_THROWS_WITH(refused("move", "0"), Contains("constraints[4].moves[0].step: 0 must come after the constraint's step 0"));
  CHECK_THROWS_WITH(refused("sheet", "roof"), Contains("actions[0].sheet: no sheet named 'roof'"));
}

TEST_CASE("across a session's steps the range-space solver updates its factor and gives the refactored answers", "[sheet][session]") {
  YAML::Node kkt_cfg = YAML::Load(kSession), rs_cfg = YAML::Load(kSession);
  kkt_cfg["solver"]["type"] = "kkt";
  rs_cfg["solver"]["type"] = "range_space";
  MetricRow kkt_row, rs_row;
  const auto kkt = run_steps(kkt_cfg, "kkt", kkt_row);
  const auto rs = run_steps(rs_cfg, "range_space", rs_row);
  REQUIRE(rs_row.at("termination") == "converged");
  REQUIRE(rs.size() == kkt.size());
  for (std::size_t k = 0; k < rs.size(); ++k) {
    INFO("step " << k << ": " << rs[k][13]);
    CHECK(std::stod(rs[k][8]) == Approx(std::stod(kkt[k][8])).epsilon(1e-8).margin(1e-10));  // energy
    // KKT keeps its factored system exactly where the rows and H stayed (nothing added or removed).
    CHECK(kkt[k][13] == (rs[k][13] == "updated (+0 -0 rows)" ? "reused" : "factored"));
  }
  CHECK(rs[0][13] == "factored");
  CHECK(rs[1][13] == "updated (+0 -0 rows)");  // a dragged target: new b, same rows
  CHECK(rs[2][13] == "updated (+0 -1 rows)");  // a point removed: a downdate
  CHECK(rs[3][13] == "updated (+0 -0 rows)");  // a rest shape installed: new f, same H
}
