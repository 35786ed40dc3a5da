// Variational space curves and sheets joined along one: the curve's basis,
// energy and fit, its own constraints, the coupling rows and the joint program.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "fairshape/bspline/joined_design.h"
#include "fairshape/bspline/knot_basis.h"
#include "fairshape/bspline/mortar_curve.h"
#include "fairshape/bspline/sheet_geometry.h"
#include "fairshape/bspline/variational_curve.h"
#include "fairshape/core/config.h"
#include "fairshape/core/error.h"
#include "fairshape/qp/qp_solver.h"
#include "sheet_test_support.h"

using namespace fairshape;
using namespace fairshape::bspline;

namespace {

// (t, t², t³) scaled: a cubic polynomial curve every cubic spline space contains.
Vec3 cubic(double t) { return {2 * t, t * t, 0.5 * t * t * t}; }
Vec3 cubic_d1(double t) { return {2, 2 * t, 1.5 * t * t}; }
Vec3 cubic_d2(double t) { return {0, 2, 3 * t}; }

std::vector<Vec3> sampled(Vec3 (*f)(double), int count) {
  std::vector<Vec3> out;
  for (int k = 0; k < count; ++k) out.push_back(f(static_cast<double>(k) / (count - 1)));
  return out;
}

double length(const std::vector<Vec3>& pts) {
  double L = 0;
  for (std::size_t k = 0; k + 1 < pts.size(); ++k) L += (pts[k + 1] - pts[k]).norm();
  return L;
}

std::unique_ptr<qp::QpSolver> make_solver(const std::string& name) {
  Config none;
  return qp::qp_solver_registry().create(name, Backend::Optimized, none);
}

}  // namespace

TEST_CASE("clamped knot basis: derivatives match finite differences on uneven knots", "[bspline][free_curve]") {
  for (int r = 1; r <= 5; ++r) {
    const ClampedKnotBasis b(0, 2, {0.3, 0.35, 1.1, 1.7}, r);
    for (double x : {0.0, 0.1, 0.32, 0.6, 1.1, 1.5, 1.99, 2.0}) {
      int first = 0, f1 = 0, f2 = 0;
      std::vector<std::vector<double>> d;
      std::vector<double> v, vp, vm;
      b.derivatives(x, std::min(r, 2), first, d);
      b.evaluate(x, f1, v);
      REQUIRE(f1 == first);
      for (std::size_t i = 0; i < v.size(); ++i) CHECK(d[0][i] == Approx(v[i]).margin(1e-14));
      // Central differences inside a knot interval (one-sided at the ends).
      const double h = 1e-6, xp = std::min(x + h, 2.0), xm = std::max(x - h, 0.0);
      if ((x > 0.29 && x < 0.36) || std::abs(x - 1.1) < 1e-9) continue;  // a knot inside the stencil
      b.evaluate(xp, f1, vp);
      b.evaluate(xm, f2, vm);
      REQUIRE(f1 == first);
      REQUIRE(f2 == first);
      const double tolerance = xp - xm < 2 * h ? 1e-3 : 1e-6;  // one-sided at the ends: O(h)
      for (std::size_t i = 0; i < v.size(); ++i) CHECK(d[1][i] == Approx((vp[i] - vm[i]) / (xp - xm)).margin(tolerance));
    }
  }
}

TEST_CASE("variational curve: the energy of a polynomial curve is its integral, at every resolution", "[bspline][free_curve]") {
  const std::vector<Vec3> pts = sampled(cubic, 41);
  const double L = length(pts);
  CurveEnergy e;
  e.alpha = 0.3;
  e.beta = 0.02;
  // ∫|X'|² = ∫ 4 + 4t² + 2.25t⁴ = 4 + 4/3 + 0.45; ∫|X''|² = ∫ 4 + 9t² = 7.
  const double expected = e.alpha / L * (4 + 4.0 / 3 + 0.45) + e.beta / (L * L * L) * 7;
  for (int spans : {1, 3, 8, 32}) {
    const VariationalCurve c({spans, 3}, pts);
    CHECK(c.design_length() == Approx(L).epsilon(1e-15));
    CHECK(curve_energy(c, e) == Approx(expected).epsilon(1e-11));
    for (double t : {0.0, 0.27, 0.5, 1.0}) {
      CHECK((c.position(t) - cubic(t)).norm() < 1e-12);
      CHECK((c.tangent(t) - cubic_d1(t) / L).norm() < 1e-11);
    }
  }
  // Degree 5 holds the cubic too.
  CHECK(curve_energy(VariationalCurve({4, 5}, pts), e) == Approx(expected).epsilon(1e-11));
  (void)cubic_d2;
}

TEST_CASE("variational curve: the least-squares fit reproduces a curve of its space", "[bspline][free_curve]") {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> d(-1, 1);
  for (int degree : {2, 3, 5}) {
    const CurveShape shape{6, degree};
    Eigen::MatrixXd q(shape.spans + degree, 3);
    for (Eigen::Index i = 0; i < q.size(); ++i) q.data()[i] = d(gen);
    const VariationalCurve truth(shape, q, 1.0);
    for (int samples : {shape.spans + degree, 65}) {
      const VariationalCurve fit(shape, truth.sample(samples));
      CHECK((fit.control_points() - q).norm() < 1e-10);
    }
  }
  // Two points: subdivided before the fit, the straight segment itself.
  const VariationalCurve line({16, 3}, std::vector<Vec3>{Vec3(0, 0, 0), Vec3(2, 1, 0)});
  CHECK(line.design_length() == Approx(std::sqrt(5.0)));
  for (double t : {0.0, 0.3, 1.0}) CHECK((line.position(t) - t * Vec3(2, 1, 0)).norm() < 1e-12);
  CHECK_THROWS_AS(VariationalCurve({4, 3}, std::vector<Vec3>{Vec3::Zero(), Vec3::Zero()}), InvalidInput);
  CHECK_THROWS_AS(VariationalCurve({0, 3}, std::vector<Vec3>{Vec3::Zero(), Vec3::UnitX()}), InvalidInput);
  CHECK_THROWS_AS(VariationalCurve({4, 6}, std::vector<Vec3>{Vec3::Zero(), Vec3::UnitX()}), InvalidInput);
}

TEST_CASE("variational curve alone: a point pulled from a straight curve gives the natural spline", "[bspline][free_curve]") {
  // Bending only, the ends held and the middle pulled by h: the minimizer of ∫|X''|² is the
  // natural cubic spline with a knot at t = 0.5 (in the space for an even number of spans),
  // ∫|X''|² dt = 48 h², whatever the resolution; a tangent constraint at the end is met too.
  const std::vector<Vec3> straight{Vec3(0, 0, 0), Vec3(2, 0, 0)};
  const double h = 0.3;
  CurveEnergy e;
  e.alpha = 0;
  e.beta = 1;
  for (int spans : {2, 8, 32}) {
    VariationalCurve c({spans, 3}, straight);
    std::vector<CurveConstraint> cs(3);
    cs[0].t = 0, cs[1].t = 1;
    cs[1].target = Vec3(2, 0, 0);
    cs[2].t = 0.5;
    cs[2].target = Vec3(1, 0, h);
    const qp::QuadraticProgram p = assemble(c, e, cs);
    for (const std::string name : {"kkt", "range_space", "qr_penalty"}) {
      auto solver = make_solver(name);
      solver->analyze(p);
      const qp::QpReport r = solver->solve(p.f, p.b);
      INFO(name << " at " << spans << " spans: " << r.summary.message);
      REQUIRE(r.summary.termination == Termination::Converged);
      c.set_control_points(r.p);
      CHECK(curve_energy(c, e) == Approx(48 * h * h / 8).epsilon(1e-6));  // L = 2: β/L³ · 48h²
      CHECK(max_error(c, cs) < 1e-9);
    }
  }
  // Tangent constraints: a quarter-circle-like bend held at both ends by its tangents.
  VariationalCurve c({8, 3}, straight);
  std::vector<CurveConstraint> cs(4);
  cs[1].t = 1;
  cs[1].target = Vec3(1, 1, 0);
  cs[2].kind = cs[3].kind = CurveConstraint::Kind::Tangent;
  cs[2].t = 0;
  cs[2].target = Vec3(1, 0, 0);
  cs[3].t = 1;
  cs[3].target = Vec3(0, 1, 0);
  const qp::QuadraticProgram p = assemble(c, e, cs);
  auto kkt = make_solver("kkt");
  kkt->analyze(p);
  c.set_control_points(kkt->solve(p.f, p.b).p);
  CHECK(max_error(c, cs) < 1e-9);
  CHECK((c.tangent(1) - Vec3(0, 1, 0)).norm() < 1e-9);
  cs[2].t = 1.5;
  CHECK_THROWS_WITH(curve_constraint_rows(c, {cs[2]}), Catch::Matchers::Contains("t must lie in [0, 1]"));
}

namespace {

// Figure 2's floor (z = 0) and wall (y = 1), 2 × 2 in design units on 8 × 8 spans, joined along
// v = 1 (design units; v = 4 in base spans) from u0 to u1 (design units) by a variational curve
// that starts straight, each sheet held at four points near its corners.
struct Fig2Joint {
  VariationalSheet floor, wall;
  VariationalCurve curve;
  std::vector<Eigen::Vector2d> uv;
  CurveEnergy curve_energy_weights;

  static VariationalSheet plane(const Vec3& origin, const Vec3& v_axis) {
    const SheetShape shape{8, 8, 3, false, Eigen::Vector2d(0.25, 0.25)};
    SheetPlacement at;
    at.origin = origin;
    at.v_axis = v_axis;
    at.size_u = at.size_v = 2;
    return VariationalSheet(shape, initial_coefficients(at, HierarchicalSurface(shape)));
  }
  Fig2Joint(double u0, double u1, int curve_spans)
      : floor(plane(Vec3(0, 0, 0), Vec3::UnitY())),
        wall(plane(Vec3(0, 1, -1), Vec3::UnitZ())),
        curve({curve_spans, 3}, std::vector<Vec3>{Vec3(u0, 1, 0), Vec3(u1, 1, 0)}),
        uv{Eigen::Vector2d(4 * u0, 4), Eigen::Vector2d(4 * u1, 4)} {}

  // The sheets' pins, the curve's ends held and its middle pulled by `pull`.
  JoinedDesign design(const Vec3& pull) {
    JoinedDesign d;
    for (VariationalSheet* s : {&floor, &wall}) {
      JoinedSheet js;
      js.sheet = s;
      js.energy.weights.alpha = 0.01 * Eigen::Matrix2d::Identity();
      for (const Eigen::Vector2d& c : {Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(7.5, 0.5), Eigen::Vector2d(0.5, 7.5), Eigen::Vector2d(7.5, 7.5)}) {
        SheetConstraint pin;
        pin.u = c.x(), pin.v = c.y();
        pin.target = s->surface().position(s->coefficients(), c.x(), c.y());
        js.constraints.push_back(pin);
      }
      d.sheets.push_back(js);
    }
    JoinedCurve jc;
    jc.curve = &curve;
    jc.energy = curve_energy_weights;
    for (double t : {0.0, 0.5, 1.0}) {
      CurveConstraint c;
      c.t = t;
      c.target = curve.position(t) + (t == 0.5 ? pull : Vec3::Zero());
      jc.constraints.push_back(c);
    }
    d.curves.push_back(jc);
    d.joints = {{0, 0, uv, "floor joint"}, {1, 0, uv, "wall joint"}};
    return d;
  }
};

}  // namespace

TEST_CASE("joined sheets: the joint is C0 and the curve's own constraints are met", "[sheet][free_curve]") {
  // Along a whole grid line with the curve on the sheets' knots, the curve's space is the
  // sheets' trace space and so is the multiplier space: the weak joint is met pointwise.
  Fig2Joint f(0, 2, 8);
  JoinedDesign d = f.design(Vec3(0, 0.35, 0.45));
  auto kkt = make_solver("kkt");
  const JoinedReport r = solve_joined(d, *kkt, Backend::Optimized);
  INFO(r.message);
  REQUIRE(r.qp.summary.termination == Termination::Converged);
  for (std::size_t j = 0; j < 2; ++j) {
    CHECK(r.joint_error[j] < 1e-9);
    CHECK(r.joint_weak[j] < 1e-10);
  }
  CHECK(r.curve_error[0] < 1e-10);
  // Both sheets' traces equal the curve: sampled directly.
  for (double t = 0; t <= 1; t += 1.0 / 64) {
    const Vec3 X = f.curve.position(t);
    CHECK((f.floor.surface().position(f.floor.coefficients(), 8 * t, 4) - X).norm() < 1e-9);
    CHECK((f.wall.surface().position(f.wall.coefficients(), 8 * t, 4) - X).norm() < 1e-9);
  }
  CHECK(max_error(r.sheet_errors[0]) < 1e-9);
  CHECK(r.sheet_rows[0] > 4);  // its pins and its joint's rows
  CHECK(r.energy() == Approx(r.sheet_energy[0] + r.sheet_energy[1] + r.curve_energy[0]));
}

TEST_CASE("joined sheets: a point pulled on the curve bends both sheets, and every solver agrees", "[sheet][free_curve]") {
  // Figure 2's joint (inset from the sheets' edges, off their knots): met in the weak sense to
  // the constraint tolerance, pointwise to the discretization. A curve finer than the sheets'
  // trace (16 spans) carries the multipliers and follows the sheets, whose traces then agree
  // exactly; a coarser one (4 spans) leads them.
  const Vec3 pull(0, 0.35, 0.45);
  for (const int spans : {4, 16}) {
    std::vector<double> energies;
    for (const std::string name : {"kkt", "range_space", "qr_penalty"}) {
      Fig2Joint f(0.125, 1.875, spans);
      JoinedDesign d = f.design(pull);
      auto solver = make_solver(name);
      const JoinedReport r = solve_joined(d, *solver, Backend::Optimized);
      INFO(name << " with " << spans << " curve spans: " << r.message << "; pointwise " << r.joint_error[0] << ", " << r.joint_error[1]);
      REQUIRE(r.qp.summary.termination == Termination::Converged);
      CHECK(r.joint_weak[0] < 1e-9);
      CHECK(r.joint_weak[1] < 1e-9);
      CHECK(r.joint_error[0] < (spans == 16 ? 1e-4 : 1e-3));
      CHECK(r.curve_error[0] < 1e-9);
      energies.push_back(r.energy());
      // The curve's middle moved by the pull, and both sheets followed it there and around it.
      CHECK((f.curve.position(0.5) - Vec3(1, 1, 0) - pull).norm() < 1e-9);
      const Vec3 floor_mid = f.floor.surface().position(f.floor.coefficients(), 4, 4);
      const Vec3 wall_mid = f.wall.surface().position(f.wall.coefficients(), 4, 4);
      CHECK((floor_mid - f.curve.position(0.5)).norm() < r.joint_error[0] + 1e-12);
      CHECK((wall_mid - f.curve.position(0.5)).norm() < r.joint_error[1] + 1e-12);
      if (spans == 16) CHECK((floor_mid - wall_mid).norm() < 1e-9);
      CHECK(f.floor.surface().position(f.floor.coefficients(), 4, 3).z() > 0.2);  // inside the floor
      CHECK(f.wall.surface().position(f.wall.coefficients(), 4, 5).y() > 1.1);    // inside the wall
      CHECK(r.sheet_energy[0] > 0.1);
      CHECK(r.sheet_energy[1] > 0.1);
      CHECK(r.curve_energy[0] > 0);
    }
    CHECK(energies[1] == Approx(energies[0]).epsilon(1e-6));
    CHECK(energies[2] == Approx(energies[0]).epsilon(1e-6));
  }
}

TEST_CASE("joined sheets: refinement drives the pointwise joint error under the tolerance, sheets and curve alike", "[sheet][free_curve]") {
  // Figure 2's inset joint with a coarse (4-span) curve: the weak joint leaves a pointwise gap
  // of about 1e-3; refinement by that gap refines the curve and both sheets near the joint
  // until it is below 2e-5.
  Fig2Joint f(0.125, 1.875, 4);
  JoinedDesign d = f.design(Vec3(0, 0.35, 0.45));
  RefinementOptions refinement;
  refinement.tolerance = 2e-5;
  refinement.max_level = 4;
  auto kkt = make_solver("kkt");
  const int floor_dofs = f.floor.surface().dof_count(), curve_dofs = f.curve.dof_count();
  const JoinedReport r = solve_joined(d, *kkt, Backend::Optimized, refinement);
  INFO(r.message << "; joint errors " << r.joint_error[0] << ", " << r.joint_error[1] << " after " << r.rounds << " rounds");
  REQUIRE(r.qp.summary.termination == Termination::Converged);
  CHECK(r.rounds > 1);
  CHECK(r.joint_error[0] <= 2e-5);
  CHECK(r.joint_error[1] <= 2e-5);
  CHECK(r.max_error() <= 2e-5);
  CHECK(r.curve_error[0] < 1e-9);
  CHECK(r.curve_spans_refined[0] > 0);
  CHECK(f.curve.dof_count() > curve_dofs);
  CHECK(r.sheet_spans_refined[0] + r.sheet_spans_refined[1] > 0);
  CHECK(f.floor.surface().dof_count() > floor_dofs);
  // Locally: the floor's corners (far from the joint at v = 4 base spans) keep their layer-0 cells.
  CHECK(f.floor.surface().leaf_cell_at(0.5, 0.5).level == 0);
  CHECK((f.curve.position(0.5) - Vec3(1, 1, 0) - Vec3(0, 0.35, 0.45)).norm() < 1e-9);
}

namespace {

// Two 2 × 1 sheets in the plane z = 0 that meet along y = 1 (the lower one's top edge, the upper
// one's bottom edge), joined there by a straight variational curve whose middle is lifted by 0.3;
// each sheet pinned along its far edge.
struct SplitPlane {
  VariationalSheet lower, upper;
  VariationalCurve curve;
  static VariationalSheet sheet(double y0) {
    const SheetShape shape{8, 4, 3, false, Eigen::Vector2d(0.25, 0.25)};
    SheetPlacement at;
    at.origin = Vec3(0, y0, 0);
    at.v_axis = Vec3::UnitY();
    at.size_u = 2, at.size_v = 1;
    return VariationalSheet(shape, initial_coefficients(at, HierarchicalSurface(shape)));
  }
  SplitPlane() : lower(sheet(0)), upper(sheet(1)), curve({8, 3}, std::vector<Vec3>{Vec3(0, 1, 0), Vec3(2, 1, 0)}) {}
  JoinedDesign design(bool tangent) {
    JoinedDesign d;
    for (auto [s, v] : {std::pair{&lower, 0.0}, std::pair{&upper, 4.0}}) {
      JoinedSheet js;
      js.sheet = s;
      for (double u : {0.0, 2.0, 4.0, 6.0, 8.0}) {
        SheetConstraint pin;
        pin.u = u, pin.v = v;
        pin.target = s->surface().position(s->coefficients(), u, v);
        js.constraints.push_back(pin);
      }
      d.sheets.push_back(js);
    }
    JoinedCurve jc;
    jc.curve = &curve;
    jc.energy.beta = 1e-3;
    for (double t : {0.0, 0.5, 1.0}) jc.constraints.push_back({CurveConstraint::Kind::Point, t, Vec3(2 * t, 1, t == 0.5 ? 0.3 : 0), ""});
    d.curves.push_back(jc);
    const std::vector<Eigen::Vector2d> lower_edge{Eigen::Vector2d(0, 4), Eigen::Vector2d(8, 4)};
    const std::vector<Eigen::Vector2d> upper_edge{Eigen::Vector2d(0, 0), Eigen::Vector2d(8, 0)};
    d.joints = {{0, 0, lower_edge, "lower joint"}, {1, 0, upper_edge, "upper joint"}};
    // The lower sheet lies right of its edge's direction (+u), the upper one left of it.
    if (tangent) d.tangent_joints = {{0, 1, false, true, "smooth"}};
    return d;
  }
  // ∂z/∂y on either side of the joint at x = 1 (one-sided, design units).
  double slope(const VariationalSheet& s, double v) const { Vec3 du, dv; s.surface().derivatives(s.coefficients(), 4, v, du, dv); return dv.z() / 0.25; }
};

}  // namespace

TEST_CASE("joined sheets: a tangent-continuous joint has no crease, and every solver agrees", "[sheet][free_curve]") {
  // Without the rows the two sheets meet at a ridge (each rises towards the lifted curve: the
  // slopes on the two sides have opposite signs); with them the slope is continuous across.
  {
    SplitPlane f;
    JoinedDesign d = f.design(false);
    auto kkt = make_solver("kkt");
    REQUIRE(solve_joined(d, *kkt, Backend::Optimized).qp.summary.termination == Termination::Converged);
    CHECK(f.slope(f.lower, 4) > 0.1);
    CHECK(f.slope(f.upper, 0) < -0.1);
  }
  std::vector<double> energies;
  for (const std::string name : {"kkt", "range_space", "qr_penalty"}) {
    SplitPlane f;
    JoinedDesign d = f.design(true);
    auto solver = make_solver(name);
    const JoinedReport r = solve_joined(d, *solver, Backend::Optimized);
    INFO(name << ": " << r.message << "; tangent error " << r.tangent_error[0]);
    REQUIRE(r.qp.summary.termination == Termination::Converged);
    CHECK(r.tangent_weak[0] < 1e-9);
    CHECK(r.tangent_error[0] < 1e-8);  // along a whole grid line the weak rows hold pointwise
    CHECK(std::abs(f.slope(f.lower, 4) - f.slope(f.upper, 0)) < 1e-8);
    CHECK(r.joint_error[0] < 1e-8);
    CHECK(r.joint_error[1] < 1e-8);
    CHECK((f.curve.position(0.5) - Vec3(1, 1, 0.3)).norm() < 1e-9);
    CHECK(f.lower.surface().position(f.lower.coefficients(), 4, 3).z() > 0.1);  // the sheets still follow the curve
    energies.push_back(r.energy());
  }
  CHECK(energies[1] == Approx(energies[0]).epsilon(1e-6));
  CHECK(energies[2] == Approx(energies[0]).epsilon(1e-6));
  // Refused: both joints on one sheet; both kept sides on one side of the curve (a wrong `keep`).
  SplitPlane f;
  JoinedDesign d = f.design(true);
  d.joints[1].sheet = 0;
  auto kkt = make_solver("kkt");
  CHECK_THROWS_WITH(solve_joined(d, *kkt, Backend::Optimized), Catch::Matchers::Contains("smooth: its two joints are on the same sheet"));
  for (const bool left : {false, true}) {
    JoinedDesign same_side = f.design(true);
    same_side.tangent_joints[0].keep_left_first = same_side.tangent_joints[0].keep_left_second = left;
    CHECK_THROWS_WITH(solve_joined(same_side, *kkt, Backend::Optimized),
                      Catch::Matchers::Contains("smooth: the kept sides lie on the same side of the curve (their outward directions are 0 degrees apart"));
  }
}

TEST_CASE("joined sheets: the rows a fine curve makes dependent are exactly so (the answer ignores rank_tolerance)", "[sheet][free_curve]") {
  // A 16-span curve has 19 functions, each sheet's trace along the joint 11: the two joints'
  // 38 rows have rank 30 in exact arithmetic, and the solvers drop 8 whatever the tolerance.
  std::vector<double> energies;
  for (const char* options : {"{rank_tolerance: 1.0e-5}", "{rank_tolerance: 1.0e-13}"}) {
    Fig2Joint f(0.125, 1.875, 16);
    JoinedDesign d = f.design(Vec3(0, 0.35, 0.45));
    Config cfg(YAML::Load(options), "");
    auto kkt = qp::qp_solver_registry().create("kkt", Backend::Optimized, cfg);
    const JoinedReport r = solve_joined(d, *kkt, Backend::Optimized);
    REQUIRE(r.qp.summary.termination == Termination::Converged);
    CHECK(r.qp.dropped_rows == 8);
    energies.push_back(r.energy());
  }
  CHECK(energies[1] == Approx(energies[0]).epsilon(1e-10));
}

TEST_CASE("joined sheets: normal constraints and bad joints are refused with their label", "[sheet][free_curve]") {
  Fig2Joint f(0, 2, 8);
  JoinedDesign d = f.design(Vec3::Zero());
  SheetConstraint n;
  n.kind = SheetConstraint::Kind::Normal;
  n.u = n.v = 2;
  n.target = Vec3::UnitZ();
  n.label = "constraints[7]";
  d.sheets[0].constraints.push_back(n);
  auto kkt = make_solver("kkt");
  CHECK_THROWS_WITH(solve_joined(d, *kkt, Backend::Optimized), Catch::Matchers::Contains("constraints[7]: normal constraints are not supported"));
  d.sheets[0].constraints.pop_back();
  d.joints[1].uv[1] = Eigen::Vector2d(9, 4);
  CHECK_THROWS_WITH(solve_joined(d, *kkt, Backend::Optimized), Catch::Matchers::Contains("wall joint: curve constraint, (u, v) point 1"));
}

namespace {

YAML::Node fig2_free() {
  YAML::Node cfg = YAML::LoadFile(test::source_path("configs/welch-witkin/fig2_free.yaml"));
  cfg.remove("smoke");  // the file's, not a run's key
  return cfg;
}

std::vector<std::vector<std::string>> run_steps(YAML::Node cfg, const std::string& id, MetricRow& row) {
  cfg["output"]["vtk"] = "none";
  return test::run_sheet_steps(cfg, std::string("free_curve_") + id, id, row);
}

}  // namespace

TEST_CASE("fig2_free: the joint is dragged, both sheets follow, the curve has its row", "[sheet][free_curve]") {
  MetricRow row;
  const auto steps = run_steps(fig2_free(), "fig2", row);
  INFO(row.at("message"));
  REQUIRE(row.at("termination") == "converged");
  REQUIRE(steps.size() == 6);  // floor, wall, curve:joint per step
  // Columns: step, sheet, dofs, levels, constraint_rows, dropped_rows, constraint_residual,
  // max_constraint_error, energy, ...
  CHECK(steps[2][1] == "curve:joint");
  CHECK(steps[2][2] == "19");
  CHECK(steps[2][4] == "3");
  for (const auto& s : steps) CHECK(std::stod(s[7]) < 1e-4);  // the joint pointwise, the curve's points
  const auto energy = [&](std::size_t k) { return std::stod(steps[k][8]); };
  CHECK(energy(3) > 10 * energy(0));  // the floor bent by the drag
  CHECK(energy(4) > 10 * energy(1));  // the wall too
  CHECK(energy(5) > energy(2));       // and the curve
  CHECK(std::stod(row.at("energy")) == Approx(energy(3) + energy(4) + energy(5)).epsilon(1e-9));
  CHECK(row.at("dofs") == "261");  // 2 x 121 + 19
  // The solved curve, written per step, ends where the drag put its middle.
  std::ifstream obj(test::scratch_path("free_curve_fig2") / "curves" / "fig2_step1_joint.obj");
  REQUIRE(obj.good());
  std::vector<Vec3> v;
  std::string line;
  while (std::getline(obj, line)) {
    std::istringstream in(line);
    std::string tag;
    double x, y, z;
    if (in >> tag >> x >> y >> z && tag == "v") v.emplace_back(x, y, z);
  }
  REQUIRE(v.size() % 2 == 1);
  CHECK((v[v.size() / 2] - Vec3(1, 1.35, 0.45)).norm() < 1e-9);
}

TEST_CASE("free curves in configs: every refusal names its key", "[sheet][free_curve]") {
  const auto refused = [](const std::string& path, const std::string& value) {
    YAML::Node cfg = fig2_free();
    if (path == "variational") cfg["curves"][0]["variational"]["spam"] = 1;
    if (path == "t") cfg["constraints"][4]["t"] = YAML::Load(value);
    if (path == "curve") cfg["constraints"][2]["curve"] = value;
    if (path == "fixed") cfg["curves"][0].remove("variational"), cfg["constraints"].remove(0), cfg["constraints"].remove(0);
    if (path == "edits") cfg["curves"][0]["edits"] = YAML::Load("[{step: 1, by: [0, 0, 1]}]");
    if (path == "estimate") cfg["refinement"]["estimate_objective_error"] = true;
    if (path == "normal") cfg["constraints"].push_back(YAML::Load("{type: normal, sheet: wall, uv: [1, 1.5], normal: [0, 1, 0]}"));
    if (path == "paper") cfg["constraints"][0]["formulation"] = "paper";
    if (path == "both") cfg["constraints"][2]["target"] = YAML::Load("[0, 0, 0]");
    if (path == "tangent") cfg["constraints"].push_back(YAML::Load("{type: curve_tangent, curve: joint, t: 0, target: [1, 0, 0], by: [0, 0, 1]}"));
    return SheetRunSpec::from_config(cfg);
  };
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(refused("variational", ""), Contains("curves[0].variational.spam: unknown key"));
  CHECK_THROWS_WITH(refused("t", "1.5"), Contains("constraints[4].t: 1.5 is out of range [0, 1]"));
  CHECK_THROWS_WITH(refused("curve", "nope"), Contains("constraints[2].curve: no space curve named 'nope'"));
  CHECK_THROWS_WITH(refused("fixed", ""), Contains("constraints[0].curve: 'joint' is not a variational curve"));
  CHECK_THROWS_WITH(refused("edits", ""), Contains("curves[0].edits: a variational curve moves by its constraints"));
  CHECK_THROWS_WITH(refused("estimate", ""), Contains("refinement.estimate_objective_error: not supported in a run with a variational curve"));
  CHECK_THROWS_WITH(refused("normal", ""), Contains("constraints[13].type: normal constraints are not supported on a sheet joined"));
  CHECK_THROWS_WITH(refused("paper", ""), Contains("constraints[0].formulation:"));
  CHECK_THROWS_WITH(refused("both", ""), Contains("constraints[2].by: give target or by, not both"));
  CHECK_THROWS_WITH(refused("tangent", ""), Contains("constraints[13].by: unknown key"));
}

TEST_CASE("a variational curve alone in a config: tangents and points, over steps", "[sheet][free_curve]") {
  // No sheet joined: the curve is its own program; a sheet elsewhere is solved as before.
  YAML::Node cfg = YAML::Load(R"(
name: alone
sheets: [{name: s, spans: [4, 4]}]
curves:
  - {name: c, points: [[0, 0, 0], [2, 0, 0]], variational: {spans: 8, alpha: 0, beta: 1}}
constraints:
  - {type: point, uv: [0.5, 0.5], by: [0, 0, 0.1]}
  - {type: point, uv: [0.1, 0.1], by: [0, 0, 0]}
  - {type: point, uv: [0.9, 0.1], by: [0, 0, 0]}
  - {type: point, uv: [0.1, 0.9], by: [0, 0, 0]}
  - {type: curve_point, curve: c, t: 0, by: [0, 0, 0]}
  - {type: curve_point, curve: c, t: 1, target: [2, 0, 0]}
  - {type: curve_point, curve: c, t: 0.5, by: [0, 0, 0], moves: [{step: 1, by: [0, 0, 0.3]}], until: 2}
  - {type: curve_tangent, curve: c, t: 0, target: [1, 0, 0], step: 2}
)");
  MetricRow row;
  const auto steps = run_steps(cfg, "alone", row);
  INFO(row.at("message"));
  REQUIRE(row.at("termination") == "converged");
  REQUIRE(steps.size() == 6);  // s and curve:c at steps 0, 1, 2
  CHECK(std::stod(steps[1][8]) == Approx(0).margin(1e-12));        // straight, held where it is
  CHECK(std::stod(steps[3][8]) == Approx(48 * 0.09 / 8).epsilon(1e-8));  // the natural spline (L = 2)
  CHECK(std::stod(steps[5][8]) == Approx(0).margin(1e-12));        // released, tangent along the line: straight again
  CHECK(steps[5][4] == "3");
}

TEST_CASE("a fine free curve on a diagonal joint: every solver agrees with KKT or says its answer is uncertain", "[sheet][free_curve]") {
  // A 32-span curve joining two 8 x 8 sheets, diagonally across one: the rows have weak
  // directions (condition estimate ~6e9). A residual of 1e-10 there still left QR-penalty's
  // answer 4e-5 off the direct solvers', reported as converged; it now refines until the answer
  // stops moving, or says it did not.
  YAML::Node cfg = YAML::Load(R"(
name: diagonal_joint
sheets:
  - {name: floor, spans: [8, 8], size: [2, 2]}
  - {name: wall, spans: [8, 8], size: [2.8284271247461903, 2], origin: [0, 0, -1], u_axis: [0.7071067811865476, 0.7071067811865476, 0], v_axis: [0, 0, 1]}
energy: {alpha: 0.01, beta: 1}
curves:
  - {name: joint, points: [[0.125, 0.125, 0], [1.875, 1.875, 0]], variational: {spans: 32, degree: 3, alpha: 0, beta: 1.0e-3}}
constraints:
  - {type: curve, sheet: floor, curve: joint, uv: [[0.125, 0.125], [1.875, 1.875]]}
  - {type: curve, sheet: wall, curve: joint, uv: [[0.1767766952966369, 1], [2.651650429449553, 1]]}
  - {type: curve_point, curve: joint, t: 0, by: [0, 0, 0]}
  - {type: curve_point, curve: joint, t: 1, by: [0, 0, 0]}
  - {type: curve_point, curve: joint, t: 0.5, by: [0, 0, 0.45]}
  - {type: point, sheet: floor, uv: [1.875, 0.125], by: [0, 0, 0]}
  - {type: point, sheet: floor, uv: [0.125, 1.875], by: [0, 0, 0]}
  - {type: point, sheet: wall, uv: [0.125, 0.125], by: [0, 0, 0]}
  - {type: point, sheet: wall, uv: [2.7, 0.125], by: [0, 0, 0]}
output: {vtk: none}
)");
  double kkt_energy = -1;
  for (const std::string solver : {"kkt", "range_space", "qr_penalty"}) {
    cfg["solver"]["type"] = solver;
    MetricRow row;
    test::run_sheet_steps(cfg, "diagonal_joint_" + solver, solver, row);
    INFO(solver << ": " << row.at("message"));
    const double energy = std::stod(row.at("energy"));
    if (solver == "kkt") {
      REQUIRE(row.at("termination") == "converged");
      kkt_energy = energy;
    } else if (row.at("termination") == "converged") {
      CHECK(std::abs(energy - kkt_energy) <= 1e-6 * kkt_energy);
    } else {
      CHECK(row.at("termination") == "ill_conditioned");
      CHECK(row.at("message").find("still moved") != std::string::npos);
    }
  }
}

TEST_CASE("a sheet joined to a free curve: its own fixed curve held off by a point is caught, as on a single sheet", "[sheet][free_curve]") {
  const auto design = [](double point_height) {
    return YAML::Load(R"(
name: joined_conflict
sheets:
  - {name: floor, spans: [8, 8], size: [2, 2]}
  - {name: wall, spans: [8, 8], size: [2.8284271247461903, 2], origin: [0, 0, -1], u_axis: [0.7071067811865476, 0.7071067811865476, 0], v_axis: [0, 0, 1]}
energy: {alpha: 0.01, beta: 1}
curves:
  - {name: joint, points: [[0.25, 0.25, 0], [1.75, 1.75, 0]], variational: {spans: 16, degree: 3, alpha: 0, beta: 1.0e-3}}
  - {name: fx, points: [[0.3, 1.2, 0.2], [0.8, 1.7, 0.2]], samples: 33}
constraints:
  - {type: curve, sheet: floor, curve: fx, uv: [[0.3, 1.2], [0.8, 1.7]]}
  - {type: point, sheet: floor, uv: [0.55, 1.45], by: [0, 0, )" + std::to_string(point_height) + R"(]}
  - {type: curve, sheet: floor, curve: joint, uv: [[0.25, 0.25], [1.75, 1.75]]}
  - {type: curve, sheet: wall, curve: joint, uv: [[0.3535533905932738, 1], [2.4748737341529163, 1]]}
  - {type: curve_point, curve: joint, t: 0, by: [0, 0, 0]}
  - {type: curve_point, curve: joint, t: 1, by: [0, 0, 0]}
  - {type: point, sheet: floor, uv: [1.875, 0.125], by: [0, 0, 0]}
  - {type: point, sheet: floor, uv: [0.125, 1.875], by: [0, 0, 0]}
  - {type: point, sheet: wall, uv: [0.125, 0.125], by: [0, 0, 0]}
  - {type: point, sheet: wall, uv: [2.7, 0.125], by: [0, 0, 0]}
output: {vtk: none}
)");
  };
  MetricRow off, on;
  test::run_sheet_steps(design(0.1), "joined_conflict_off", "off", off);
  INFO(off.at("message"));
  CHECK(off.at("termination") == "constraints_unmet");
  CHECK(off.at("message").find("constraints[1] (a point) lies on the path of curve constraints[0]") != std::string::npos);
  const auto on_steps = test::run_sheet_steps(design(0.2), "joined_conflict_on", "on", on);
  INFO(on.at("message"));
  CHECK(on.at("termination") == "converged");
  // The floor's own curve is judged and reported in steps.csv (curve_error is the fourth column
  // from the end), as on a single sheet.
  REQUIRE(!on_steps.empty());
  CHECK(on_steps[0][1] == "floor");
  CHECK(std::stod(on_steps[0][on_steps[0].size() - 4]) > 0);
}
