// Variational space curves and sheets joined along one (issue 23, part 5): the curve's basis,
// energy and fit, its own constraints, the coupling rows and the joint program.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "bspline/knot_basis.h"
#include "bspline/mortar_curve.h"
#include "bspline/variational_curve.h"
#include "core/config.h"
#include "core/error.h"
#include "qp/qp_solver.h"

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
