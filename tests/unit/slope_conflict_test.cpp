// Tangent and normal constraints on a curve constraint's path compared with the curve's slope
// (bspline/slope_conflict.h): a contradiction is constraints_unmet with the default options,
// however the path runs; a consistent derivative (across the curve, or the curve's own slope
// on a lifted, sampled curve) is not.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include <yaml-cpp/yaml.h>

#include "fairshape/bspline/slope_conflict.h"
#include "fairshape/experiment/kinds/sheet/sheet_run.h"
#include "fairshape/experiment/run_outputs.h"
#include "test_support.h"

using namespace fairshape;
namespace fs = std::filesystem;

namespace {

MetricRow run_sheet(const YAML::Node& cfg, const std::string& id) {
  const fs::path dir = test::scratch_dir(std::string("slope_conflict_") + id);
  create_run_folders(dir.string());
  SheetRunSpec spec = SheetRunSpec::from_config(cfg);
  return execute_sheet_run(spec, RunOutputs{dir.string(), id, true, nullptr});
}

// The flat diagonal of an 8 x 8-span sheet of size 2 (design units: uv = world xy), pinned at
// its corners, with `extra` constraints; no refinement tolerance (how every figure runs).
YAML::Node diagonal(const std::string& solver, const std::string& extra, const std::string& edits = "[]") {
  return YAML::Load(R"(
name: slope
sheets: [{name: s, spans: [8, 8], size: [2, 2]}]
energy: {alpha: 0.01, beta: 1}
output: {vtk: none}
solver: {type: )" + solver + R"(}
curves: [{name: d, from_surface: {sheet: s, uv: [[0.25, 0.25], [1.75, 1.75]]}, samples: 65, edits: )" + edits + R"(}]
constraints:
  - {type: point, uv: [0.125, 0.125], by: [0, 0, 0]}
  - {type: point, uv: [1.875, 0.125], by: [0, 0, 0]}
  - {type: point, uv: [0.125, 1.875], by: [0, 0, 0]}
  - {type: point, uv: [1.875, 1.875], by: [0, 0, 0]}
  - {type: curve, curve: d}
)" + extra);
}

// A stream, not "[" + std::to_string(x) + …: GCC 12 reports a false -Wrestrict in that chain.
std::string vec(double x, double y, double z) {
  std::ostringstream os;
  os.precision(17);
  os << '[' << x << ", " << y << ", " << z << ']';
  return os.str();
}

}  // namespace

TEST_CASE("the slope mismatch of a normal on a diagonal curve is the least-squares residual of the conditions on J", "[sheet][slope_conflict]") {
  // Curve rows (D_u w + D_v w)/√2 = D' with D' the unit slope along the diagonal, normal rows
  // n·D_u w = n·D_v w = 0. With a = (D_u w + D_v w)/√2 the residual² is |a − D'|² + (n·a)² (the
  // difference of the columns is free), least at a's n-component β/2: |β|/√2 with β = n·D'.
  bspline::SheetConstraint curve;
  curve.kind = bspline::SheetConstraint::Kind::Curve;
  curve.curve.uv = {{1, 1}, {7, 7}};  // spans; span_size 0.25: (0.25, 0.25) to (1.75, 1.75)
  curve.curve.space = {{0.25, 0.25, 0}, {1.75, 1.75, 0}};
  for (const double s : {0.0, 0.05, 0.3, 2.0}) {
    bspline::SheetConstraint normal;
    normal.kind = bspline::SheetConstraint::Kind::Normal;
    normal.u = normal.v = 4;
    normal.target = Vec3(s / std::sqrt(2.0), s / std::sqrt(2.0), 1);
    const double expected = s / std::sqrt(1 + s * s) / std::sqrt(2.0);
    const auto m = bspline::slope_conflict({curve, normal}, {0.25, 0.25}, 1e-6, 1e-12);
    INFO("tilt " << s);
    if (s == 0) {
      CHECK(!m);
      continue;
    }
    REQUIRE(m);
    CHECK(m->at.gap == Approx(expected).epsilon(1e-12));
    CHECK(m->at.uv.isApprox(Eigen::Vector2d(4, 4)));
    CHECK(m->curve_slope.isApprox(Vec3(1, 1, 0) / std::sqrt(2.0)));
    // Tilted across the curve instead: consistent.
    normal.target = Vec3(s / std::sqrt(2.0), -s / std::sqrt(2.0), 1);
    CHECK(!bspline::slope_conflict({curve, normal}, {0.25, 0.25}, 1e-6, 1e-12));
  }
}

TEST_CASE("a normal tilted along a flat diagonal curve is constraints_unmet for every solver, without a refinement tolerance",
          "[sheet][slope_conflict]") {
  const double s = 0.3 / std::sqrt(2.0);
  for (const std::string solver : {"kkt", "range_space", "qr_penalty"}) {
    INFO(solver);
    const MetricRow along = run_sheet(diagonal(solver, "  - {type: normal, uv: [1, 1], normal: " + vec(s, s, 1) + "}\n"), "along");
    INFO(along.at("message"));
    CHECK(along.at("termination") == "constraints_unmet");
    CHECK(along.at("message").find("constraints[5] (a normal) lies on the path of curve constraints[4] at (u, v) = (1.00e+00, 1.00e+00)") !=
          std::string::npos);
    // Tilted across the curve the tangent plane still holds the curve's direction: legal.
    const MetricRow across = run_sheet(diagonal(solver, "  - {type: normal, uv: [1, 1], normal: " + vec(s, -s, 1) + "}\n"), "across");
    INFO(across.at("message"));
    CHECK(across.at("termination") == "converged");
  }
}

TEST_CASE("tangents on a diagonal curve: one tilted tangent is legal, both tilted contradict the curve's slope", "[sheet][slope_conflict]") {
  // J e = D' along the diagonal leaves one column of J free when only the other is given; with
  // both given, (D_u w + D_v w)/√2 must equal the curve's slope.
  const std::string u = "  - {type: tangent, uv: [1, 1], direction: u, target: [1, 0, 0.3]}\n";
  const std::string v = "  - {type: tangent, uv: [1, 1], direction: v, target: [0, 1, 0.3]}\n";
  const std::string v_legal = "  - {type: tangent, uv: [1, 1], direction: v, target: [0, 1, -0.3]}\n";
  const MetricRow one = run_sheet(diagonal("kkt", u), "one_tangent");
  INFO(one.at("message"));
  CHECK(one.at("message").find("(a tangent) lies on the path") == std::string::npos);
  const MetricRow both = run_sheet(diagonal("kkt", u + v), "two_tangents");
  INFO(both.at("message"));
  CHECK(both.at("termination") == "constraints_unmet");
  CHECK(both.at("message").find("(a tangent) lies on the path of curve constraints[4]") != std::string::npos);
  const MetricRow legal = run_sheet(diagonal("kkt", u + v_legal), "two_tangents_legal");
  INFO(legal.at("message"));
  CHECK(legal.at("message").find("(a tangent) lies on the path") == std::string::npos);
}

TEST_CASE("a normal agreeing with a lifted, sampled curve's slope is no conflict", "[sheet][slope_conflict]") {
  // The diagonal lifted by a cosine bump 0.3 high (edit radius 0.6 in t); the normal at t = 0.3
  // is perpendicular to the smooth curve's tangent there. The sampled curve's centred slope is
  // within the tolerance of the smooth one; a one-sided chord would not be.
  const double t = 0.3, length = 1.5 * std::sqrt(2.0);
  const double dz_dt = -0.15 * M_PI / 0.6 * std::sin(M_PI * (t - 0.5) / 0.6);
  const double slope = dz_dt / length;  // dz per unit length along the path
  const double c = 0.25 + 1.5 * t;
  const std::string normal = "  - {type: normal, uv: [" + std::to_string(c) + ", " + std::to_string(c) + "], normal: " +
                             vec(-slope / std::sqrt(2.0), -slope / std::sqrt(2.0), 1) + "}\n";
  const MetricRow r = run_sheet(diagonal("kkt", normal, "[{step: 0, t: 0.5, radius: 0.6, by: [0, 0, 0.3]}]"), "lifted");
  INFO(r.at("message"));
  CHECK(r.at("message").find("(a normal) lies on the path") == std::string::npos);
}
