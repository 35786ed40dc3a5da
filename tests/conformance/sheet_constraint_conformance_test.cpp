// Every registered kind of a sheet config's constraints (constraint_kinds.h) has an example here
// — a new kind fails this test until it has one — that its reader reads into the right spec, whose
// keys `fairshape list` documents, which refuses an unknown key naming it, and whose config runs
// to a converged design through the session.
#include <catch2/catch.hpp>

#include <map>
#include <string>
#include <variant>

#include <yaml-cpp/yaml.h>

#include "fairshape/experiment/kinds/sheet/constraint_kinds.h"
#include "fairshape/experiment/kinds/sheet/sheet_steps.h"

using namespace fairshape;
using Catch::Matchers::Contains;

namespace {

// A 2 × 2 sheet held at its corners, a fixed space curve across it; {} is the kind's entry.
const char* const kSheet = R"(
name: kind
sheets: [{name: s, spans: [8, 8], size: [2, 2]}]
energy: {alpha: 0.01, beta: 1}
curves: [{name: c, points: [[0.5, 1, 0.1], [1, 1, 0.2], [1.5, 1, 0.1]]}]
output: {vtk: none}
constraints:
  - {type: point, uv: [0.125, 0.125], by: [0, 0, 0]}
  - {type: point, uv: [1.875, 0.125], by: [0, 0, 0]}
  - {type: point, uv: [0.125, 1.875], by: [0, 0, 0]}
  - {type: point, uv: [1.875, 1.875], by: [0, 0, 0]}
  - {})";

// Two sheets joined along a variational curve (configs/welch-witkin/smooth_joint.yaml, smaller).
const char* const kJoined = R"(
name: kind
sheets:
  - {name: lower, spans: [4, 2], size: [2, 1], origin: [0, 0, 0]}
  - {name: upper, spans: [4, 2], size: [2, 1], origin: [0, 1, 0]}
energy: {alpha: 0.01, beta: 1}
curves: [{name: ridge, points: [[0, 1, 0], [2, 1, 0]], variational: {spans: 4, degree: 3, alpha: 0, beta: 1.0e-3}}]
output: {vtk: none}
constraints:
  - {type: curve, sheet: lower, curve: ridge, uv: [[0, 1], [2, 1]]}
  - {type: curve, sheet: upper, curve: ridge, uv: [[0, 0], [2, 0]]}
  - {type: curve_point, curve: ridge, t: 0, by: [0, 0, 0]}
  - {type: curve_point, curve: ridge, t: 1, by: [0, 0, 0]}
  - {type: point, sheet: lower, uv: [1, 0], by: [0, 0, 0]}
  - {type: point, sheet: upper, uv: [1, 1], by: [0, 0, 0]}
  - {})";

struct Example {
  const char* config;
  const char* entry;
  int variant;  // 0: a sheet's constraint, 1: a variational curve's own, 2: tangent continuity
};

const std::map<std::string, Example>& examples() {
  static const std::map<std::string, Example> e{
      {"point", {kSheet, "{type: point, uv: [1, 0.75], by: [0, 0, 0.2]}", 0}},
      {"tangent", {kSheet, "{type: tangent, uv: [1, 0.5], direction: u, target: [1, 0, 0.2]}", 0}},
      {"normal", {kSheet, "{type: normal, uv: [1, 0.5], normal: [0.1, 0, 1]}", 0}},
      {"curve", {kSheet, "{type: curve, curve: c, uv: [[0.5, 1], [1, 1], [1.5, 1]]}", 0}},
      {"ribbon", {kSheet, "{type: ribbon, curve: c, uv: [[0.5, 1], [1, 1], [1.5, 1]], cross_tangent: [0, 1, 0]}", 0}},
      {"offset", {kSheet, "{type: offset, uv: [1.5, 0.5], from: [0.5, 0.5], offset: [1, 0, 0.2]}", 0}},
      // Held where it is: lifted, a region on an 8 × 8 sheet ends ill_conditioned (README, "Offsets,
      // ribbons and regions").
      {"region", {kSheet, "{type: region, corners: [[0.75, 0.5], [1.25, 1.0]], surface: initial, by: [0, 0, 0]}", 0}},
      {"curve_point", {kJoined, "{type: curve_point, curve: ridge, t: 0.5, by: [0, 0, 0.2]}", 1}},
      {"curve_tangent", {kJoined, "{type: curve_tangent, curve: ridge, t: 0.5, target: [1, 0, 0]}", 1}},
      {"tangent_continuity", {kJoined, "{type: tangent_continuity, curve: ridge, sheets: [lower, upper], keep: [right, left]}", 2}},
  };
  return e;
}

YAML::Node with_entry(const Example& ex, const std::string& entry) {
  YAML::Node cfg = YAML::Load(ex.config);
  cfg["constraints"][cfg["constraints"].size() - 1] = YAML::Load(entry);
  return cfg;
}

}  // namespace

TEST_CASE("every registered sheet constraint kind: documented, read, strict about its keys, and solved to convergence",
          "[sheet][constraint_kinds]") {
  const SheetConstraintRegistry reg = sheet_constraint_registry();
  REQUIRE(reg.names().size() >= 10);
  for (const std::string& name : reg.names()) {
    INFO("kind " << name);
    const auto it = examples().find(name);
    REQUIRE(it != examples().end());  // a newly registered kind needs its example here
    const Example& ex = it->second;
    // `fairshape list` prints its keys: every kind documents at least one.
    for (const auto& e : reg.entries())
      if (e.name == name) CHECK_FALSE(reg.options(e).empty());
    // Read into the right spec.
    YAML::Node entry = YAML::Load(ex.entry);
    Config c(entry, "constraints[0]");
    const SheetConfigConstraint read = read_sheet_config_constraint(c, {"constraints[0]", "s", 0});
    CHECK(static_cast<int>(read.spec.index()) == ex.variant);
    // An unknown key is refused, naming it.
    YAML::Node bad = YAML::Load(ex.entry);
    bad["bogus_key"] = 1;
    CHECK_THROWS_WITH(SheetRunSpec::from_config(with_entry(ex, YAML::Dump(bad))), Contains("bogus_key"));
    // The whole config runs through the session, every step converged.
    SheetConfigSteps steps(SheetRunSpec::from_config(with_entry(ex, ex.entry)));
    while (steps.next_step() < steps.steps()) {
      const SheetConfigStep st = steps.advance();
      INFO("step " << st.step << ": " << st.result.summary.message);
      CHECK(st.result.summary.succeeded());
      CHECK(st.result.solved_any());
      for (const FreeCurveStep& fc : st.free_curves) CHECK(is_success(fc.termination));
    }
  }
}

TEST_CASE("an unknown sheet constraint type is refused with every registered one named", "[sheet][constraint_kinds]") {
  YAML::Node cfg = YAML::Load(kSheet);
  cfg["constraints"][4] = YAML::Load("{type: pointt, uv: [1, 1], by: [0, 0, 0]}");
  const SheetConstraintRegistry reg = sheet_constraint_registry();
  try {
    (void)SheetRunSpec::from_config(cfg);
    FAIL("accepted type: pointt");
  } catch (const InvalidConfig& e) {
    const std::string what = e.what();
    CHECK_THAT(what, Contains("constraints[4].type"));
    for (const std::string& name : reg.names()) CHECK_THAT(what, Contains(name));
  }
}
