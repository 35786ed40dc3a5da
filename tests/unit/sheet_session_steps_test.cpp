// Welch & Witkin's modelling session driven step by step from C++ (bspline/sheet_session.h)
// gives the config run of the same steps bit for bit, and each step verifies itself.
#include <catch2/catch.hpp>

#include <string>

#include <yaml-cpp/yaml.h>

#include "fairshape/bspline/sheet_session.h"
#include "fairshape/experiment/kinds/sheet/sheet_steps.h"
#include "fairshape/qp/kkt_solver.h"
#include "sheet_test_support.h"

using namespace fairshape;
using bspline::SheetConstraint;
using Catch::Matchers::Contains;

namespace {

// Steps: 0 the corner pins, a lifted point, a second point and a curve; 1 the lifted point
// dragged; 2 the second point removed; 3 the shape installed as rest; 4 the rest shape melted.
const std::string kConfig = std::string(R"(
name: steps
sheets: [{name: s, spans: [8, 8], size: [2, 2]}]
energy: {alpha: 0.01, beta: 1}
curves: [{name: ridge, points: [[0.5, 1.5, 0.1], [1.0, 1.625, 0.3], [1.5, 1.5, 0.1]]}]
output: {vtk: none}
constraints:)") + test::kCornerPinsYaml + R"(
  - {type: point, uv: [1, 0.75], by: [0, 0, 0.25], moves: [{step: 1, by: [0, 0.125, 0.25]}]}
  - {type: point, uv: [0.5, 1], by: [0, 0, -0.125], until: 2}
  - {type: curve, curve: ridge, uv: [[0.5, 1.5], [1.0, 1.625], [1.5, 1.5]]}
actions:
  - {step: 3, do: install_rest_shape}
  - {step: 4, do: melt_rest_shape}
)";

SheetConstraint point(const SheetSession& s, double u, double v, const Vec3& by) {
  SheetConstraint c;
  c.u = u / 0.25, c.v = v / 0.25;  // design units to base spans (a span is 0.25)
  c.target = by;
  c.target += s.initial_surface(0).position(s.initial_coefficients(0), c.u, c.v);  // as a config's `by:`
  return c;
}

SheetSession by_hand(const SheetRunSpec& spec) {
  std::vector<bspline::VariationalSheet> sheets{test::flat_sheet()};
  SheetSessionOptions options;
  options.energy = spec.energy;
  Config none;
  return SheetSession({"s"}, std::move(sheets), options, qp::qp_solver_registry().create("kkt", Backend::Optimized, none));
}

}  // namespace

TEST_CASE("a SheetSession driven step by step equals the config run of the same steps, bit for bit", "[sheet][session]") {
  const YAML::Node cfg = YAML::Load(kConfig);
  SheetConfigSteps config(SheetRunSpec::from_config(cfg));
  REQUIRE(config.steps() == 5);
  std::vector<Eigen::MatrixXd> expected;
  for (int k = 0; k < config.steps(); ++k) {
    const SheetConfigStep st = config.advance();
    INFO("config step " << k << ": " << st.result.summary.message);
    REQUIRE(st.result.summary.succeeded());
    expected.push_back(config.session().sheet(0).coefficients());
  }
  // The same steps by hand: the constraints added one at a time (each a step), then dragged,
  // removed, installed and melted.
  const SheetRunSpec spec = SheetRunSpec::from_config(cfg);
  SheetSession s = by_hand(spec);
  for (const auto& [u, v] : {std::pair{0.125, 0.125}, {1.875, 0.125}, {0.125, 1.875}, {1.875, 1.875}})
    REQUIRE(s.add({0, point(s, u, v, Vec3::Zero())}).summary.succeeded());
  const SheetStep lifted = s.add({0, point(s, 1, 0.75, Vec3(0, 0, 0.25))});
  REQUIRE(lifted.added == std::vector<SheetHandle>{4});
  const SheetStep second = s.add({0, point(s, 0.5, 1, Vec3(0, 0, -0.125))});
  SheetConstraint ridge = spec.constraints.back().constraint;  // its (u, v) in base spans, as read
  ridge.curve.space = {Vec3(0.5, 1.5, 0.1), Vec3(1.0, 1.625, 0.3), Vec3(1.5, 1.5, 0.1)};
  const SheetStep step0 = s.add({0, ridge});
  REQUIRE(step0.summary.succeeded());
  CHECK(s.sheet(0).coefficients() == expected[0]);
  const Vec3 dragged = s.constraint(4).constraint.target + Vec3(0, 0.125, 0.25);
  const SheetStep step1 = s.move(4, dragged);
  CHECK(s.sheet(0).coefficients() == expected[1]);
  // The drag kept the factorization (same rows, same energy: new targets only).
  CHECK(dynamic_cast<qp::KktSolver&>(s.solver()).reused_factorization());
  // What the drag asked, next to what the sheet achieved, measured on it.
  const auto handle4 = std::find_if(step1.checks.begin(), step1.checks.end(), [](const auto& c) { return c.handle == 4; });
  REQUIRE(handle4 != step1.checks.end());
  CHECK(handle4->asked == dragged);
  CHECK((handle4->achieved - dragged).norm() <= 1e-9);
  CHECK(step1.max_constraint_error <= 1e-2);  // the curve's, in the mean per cell (README: mortar rows)
  CHECK(step1.solve_s > 0);
  CHECK(step1.check_s > 0);
  s.remove(second.added.at(0));
  CHECK(s.sheet(0).coefficients() == expected[2]);
  const SheetStep installed = s.install_rest_shape();
  CHECK(s.sheet(0).coefficients() == expected[3]);
  CHECK(installed.energy == Approx(0).margin(1e-9));  // the minimizer of eq. 6 about itself
  s.melt();
  CHECK(s.sheet(0).coefficients() == expected[4]);
}

TEST_CASE("a refused session step names why and leaves the session as it was", "[sheet][session]") {
  const SheetRunSpec spec = SheetRunSpec::from_config(YAML::Load(kConfig));
  SheetSession s = by_hand(spec);
  REQUIRE(s.add({0, point(s, 1, 1, Vec3(0, 0, 0.2))}).summary.succeeded());
  const Eigen::MatrixXd before = s.sheet(0).coefficients();
  SheetConstraint outside = point(s, 1, 1, Vec3::Zero());
  outside.u = 9;
  CHECK_THROWS_WITH(s.add({0, outside}), Contains("outside the sheet's domain"));
  CHECK_THROWS_WITH(s.move(7, Vec3::Zero()), Contains("no constraint 7"));
  CHECK_THROWS_WITH(s.move_curve(0, {Vec3::Zero(), Vec3::UnitX()}), Contains("not a curve constraint"));
  CHECK_THROWS_WITH(s.add({3, point(s, 1, 1, Vec3::Zero())}), Contains("no sheet 3"));
  CHECK(s.constraints().size() == 1);
  CHECK(s.sheet(0).coefficients() == before);
  // The next handle is still 1: refused steps make none.
  CHECK(s.add({0, point(s, 0.5, 0.5, Vec3::Zero())}).added == std::vector<SheetHandle>{1});
}

TEST_CASE("refine by constraint error: a session step that refines where the error is above the tolerance", "[sheet][session]") {
  const SheetRunSpec spec = SheetRunSpec::from_config(YAML::Load(kConfig));
  SheetSession s = by_hand(spec);
  SheetConstraint ridge = spec.constraints.back().constraint;
  ridge.curve.space = {Vec3(0.5, 1.5, 0.1), Vec3(1.0, 1.625, 0.3), Vec3(1.5, 1.5, 0.1)};
  const SheetStep coarse = s.add({0, ridge});
  REQUIRE(coarse.summary.succeeded());
  const double tolerance = 0.25 * coarse.max_constraint_error;
  const int dofs = s.sheet(0).surface().dof_count();
  const SheetStep refined = s.refine(tolerance);
  INFO(refined.summary.message);
  REQUIRE(refined.summary.succeeded());
  CHECK(refined.sheets.at(0).report.spans_refined > 0);
  CHECK(s.sheet(0).surface().dof_count() > dofs);
  CHECK(refined.max_constraint_error <= tolerance);
  CHECK(s.options().refinement.tolerance == 0);  // the session's own tolerance is kept
}
