// Welch & Witkin's hierarchical B-spline surfaces: basis, refinement, energy, constraints.
#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>
#include <random>

#include "fairshape/bspline/hierarchical_surface.h"
#include "fairshape/bspline/surface_constraints.h"
#include "fairshape/bspline/thin_plate_energy.h"
#include "fairshape/bspline/uniform_basis.h"
#include "fairshape/bspline/variational_sheet.h"
#include "fairshape/core/config.h"
#include "fairshape/core/error.h"
#include "fairshape/qp/qp_solver.h"

using namespace fairshape;
using namespace fairshape::bspline;

namespace {

// Coefficients that make the surface (u, v, 0): the control points at their Greville abscissae
// (linear precision), on the base layer only.
Eigen::MatrixXd linear_coefficients(const HierarchicalSurface& s) {
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(s.dof_count(), 3);
  const double shift = (s.degree() - 1) / 2.0;
  for (int k = 0; k < s.dof_count(); ++k) {
    const ControlId c = s.dofs()[k];
    REQUIRE(c.level == 0);
    P(k, 0) = c.i - shift;
    P(k, 1) = c.j - shift;
  }
  return P;
}

Eigen::MatrixXd random_coefficients(int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> d(-1, 1);
  Eigen::MatrixXd P(n, 3);
  for (Eigen::Index i = 0; i < P.size(); ++i) P.data()[i] = d(gen);
  return P;
}

// A sheet with two refined layers (a block of base spans, then part of it again).
HierarchicalSurface refined_sheet(Eigen::MatrixXd* P = nullptr, bool periodic = false) {
  HierarchicalSurface s({periodic ? 6 : 5, 4, 3, periodic});
  if (P) *P = random_coefficients(s.dof_count(), 3);
  SparseMatrix T = s.refine({{0, 1, 1}, {0, 2, 1}, {0, 2, 2}});
  if (P) *P = T * *P;
  T = s.refine({{1, 4, 3}, {1, 5, 3}});
  if (P) *P = T * *P;
  return s;
}

double smallest_eigenvalues_count(const SparseMatrix& H, double tolerance) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig{Eigen::MatrixXd(H)};
  int count = 0;
  for (Eigen::Index i = 0; i < eig.eigenvalues().size(); ++i) count += eig.eigenvalues()(i) < tolerance;
  return count;
}

}  // namespace

TEST_CASE("uniform B-spline basis: partition of unity, derivatives, refinement mask", "[bspline]") {
  for (int r = kMinDegree; r <= kMaxDegree; ++r)
    for (double t : {0.0, 0.3, 0.77, 1.0}) {
      const SpanBasis b = uniform_span_basis(r, t);
      double sum = 0, d1 = 0, d2 = 0;
      for (int i = 0; i <= r; ++i) sum += b.value[i], d1 += b.d1[i], d2 += b.d2[i];
      CHECK(sum == Approx(1).epsilon(1e-14));
      CHECK(std::abs(d1) < 1e-13);
      if (r > 2 || (t > 0 && t < 1)) CHECK(std::abs(d2) < 1e-12);  // a quadratic's d2 jumps at knots
      // Finite differences agree with the analytic derivative.
      const double h = 1e-6;
      if (t > 0.1 && t < 0.9) {
        const SpanBasis p = uniform_span_basis(r, t + h), m = uniform_span_basis(r, t - h);
        for (int i = 0; i <= r; ++i) CHECK(b.d1[i] == Approx((p.value[i] - m.value[i]) / (2 * h)).margin(1e-7));
      }
    }
  const SpanBasis cubic = uniform_span_basis(3, 0);
  CHECK(cubic.value[0] == Approx(1.0 / 6));
  CHECK(cubic.value[1] == Approx(4.0 / 6));
  CHECK(cubic.value[2] == Approx(1.0 / 6));
  // B(x) = Σ mask_k B(2x − k) at sample points.
  for (int r = kMinDegree; r <= kMaxDegree; ++r) {
    const std::vector<double> mask = refinement_mask(r);
    for (double x : {0.2, 1.3, 2.5, 3.9}) {
      double fine = 0;
      for (int k = 0; k <= r + 1; ++k) fine += mask[k] * cardinal_bspline(r, 2 * x - k);
      CHECK(fine == Approx(cardinal_bspline(r, x)).margin(1e-14));
    }
  }
}

TEST_CASE("Gauss-Legendre rules are exact to degree 2n-1", "[bspline]") {
  for (int n = 1; n <= 6; ++n) {
    const GaussRule g = gauss_legendre(n);
    for (int k = 0; k <= 2 * n - 1; ++k) {
      double q = 0;
      for (int i = 0; i < n; ++i) q += g.weights[i] * std::pow(g.nodes[i], k);
      CHECK(q == Approx(1.0 / (k + 1)).epsilon(1e-13));
    }
  }
}

TEST_CASE("refinement keeps the surface: an all-zero layer and the transferred coefficients change nothing", "[bspline]") {
  HierarchicalSurface s({5, 4, 3, false});
  const Eigen::MatrixXd P0 = random_coefficients(s.dof_count(), 1);
  const HierarchicalSurface before = s;
  const SparseMatrix T = s.refine({{0, 1, 1}, {0, 2, 1}, {0, 2, 2}});
  REQUIRE(s.level_count() == 2);
  REQUIRE(s.span_count(1) > 0);
  const Eigen::MatrixXd P1 = T * P0;
  // Coarse functions inside the refined region were handed to the finer layer.
  int fine = 0;
  for (const ControlId& c : s.dofs()) fine += c.level == 1;
  CHECK(fine > 0);
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> du(0, 5), dv(0, 4);
  for (int k = 0; k < 200; ++k) {
    const double u = du(gen), v = dv(gen);
    CHECK((s.position(P1, u, v) - before.position(P0, u, v)).norm() < 1e-12);
  }
  // Linear precision survives refinement exactly.
  HierarchicalSurface lin({5, 4, 3, false});
  Eigen::MatrixXd L = linear_coefficients(lin);
  L = lin.refine({{0, 2, 2}}) * L;
  for (int k = 0; k < 50; ++k) {
    const double u = du(gen), v = dv(gen);
    CHECK((lin.position(L, u, v) - Vec3(u, v, 0)).norm() < 1e-12);
  }
  CHECK_THROWS_AS(s.refine({{2, 0, 0}}), InvalidInput);
}

TEST_CASE("the summed surface is C2 across layer boundaries", "[bspline]") {
  for (const bool periodic : {false, true}) {
    Eigen::MatrixXd P;
    const HierarchicalSurface s = refined_sheet(&P, periodic);
    // Random coefficients on every layer, including the refined ones.
    P = random_coefficients(s.dof_count(), 9);
    // Second derivatives are cubic at most along a line inside one leaf cell: extrapolate each
    // side to the cell boundary from four points in the same cell (exact for cubics); the two
    // limits must agree. Every layer-2 grid line in u and in v is checked.
    const auto second = [&](double u, double v) {
      BasisRow row;
      s.basis(u, v, row);
      Eigen::Vector3d d = Eigen::Vector3d::Zero();  // z component of w_uu, w_uv, w_vv
      for (const BasisEntry& e : row) d += Eigen::Vector3d(e.duu, e.duv, e.dvv) * P(e.dof, 2);
      return d;
    };
    const auto limit = [&](double u, double v, double du, double dv) {  // from the side (du, dv) points to
      return (4 * second(u + du, v + dv) - 6 * second(u + 2 * du, v + 2 * dv) + 4 * second(u + 3 * du, v + 3 * dv) -
              second(u + 4 * du, v + 4 * dv)).eval();
    };
    const double h = 0.02;
    double worst = 0, scale = 0;
    for (double line = 0.25; line < 3.9; line += 0.25)
      for (double x : {0.3, 1.1, 1.6, 2.45, 3.7}) {
        worst = std::max(worst, (limit(line, x, -h, 0) - limit(line, x, h, 0)).norm());  // across u = line
        worst = std::max(worst, (limit(x, line, 0, -h) - limit(x, line, 0, h)).norm());  // across v = line
        scale = std::max(scale, second(line, x).norm());
      }
    REQUIRE(scale > 1);  // the random layers do bend the surface
    INFO("periodic " << periodic);
    CHECK(worst < 1e-10);
  }
}

TEST_CASE("thin plate H: exact quadrature, symmetric PSD with the expected null space, reference equals optimized", "[bspline]") {
  TensionWeights w;
  w.alpha << 0.7, 0.2, 0.2, 0.4;
  w.beta << 1.0, 0.3, 0.3, 0.6;
  Eigen::MatrixXd dummy;
  HierarchicalSurface s = refined_sheet(&dummy);
  const SparseMatrix H = thin_plate_hessian(s, w, Backend::Optimized);
  const SparseMatrix Href = thin_plate_hessian(s, w, Backend::Reference);
  CHECK((H - Href).norm() <= 1e-12 * H.norm());
  CHECK((H - SparseMatrix(H.transpose())).norm() <= 1e-13 * H.norm());
  const SparseMatrix K = thin_plate_square_root(s, w);
  CHECK((SparseMatrix(K.transpose() * K) - H).norm() <= 1e-12 * H.norm());

  // A polynomial surface in the spline space: w(u, v) = u² + u v − 0.3 v³ (z only), fitted by
  // interpolation at many points (exact, the spline space contains cubics).
  const auto poly = [](double u, double v) { return u * u + u * v - 0.3 * v * v * v; };
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> du(0, 5), dv(0, 4);
  Triplets t;
  std::vector<double> rhs;
  BasisRow row;
  for (int k = 0; k < 6 * s.dof_count(); ++k) {
    const double u = du(gen), v = dv(gen);
    s.basis(u, v, row);
    for (const BasisEntry& e : row) t.emplace_back(k, e.dof, e.value);
    rhs.push_back(poly(u, v));
  }
  SparseMatrix B(static_cast<Eigen::Index>(rhs.size()), s.dof_count());
  B.setFromTriplets(t.begin(), t.end());
  const Eigen::MatrixXd BtB = Eigen::MatrixXd(SparseMatrix(B.transpose() * B));
  const Eigen::VectorXd p = BtB.ldlt().solve(Eigen::VectorXd(B.transpose() * Eigen::Map<Eigen::VectorXd>(rhs.data(), rhs.size())));
  // The analytic integral, by a 10-point Gauss rule (exact for these degrees) on the whole domain.
  const GaussRule g = gauss_legendre(10);
  double exact = 0;
  for (std::size_t a = 0; a < 10; ++a)
    for (std::size_t b = 0; b < 10; ++b) {
      const double u = 5 * g.nodes[a], v = 4 * g.nodes[b], wt = 20 * g.weights[a] * g.weights[b];
      const double wu = 2 * u + v, wv = u - 0.9 * v * v, wuu = 2, wuv = 1, wvv = -1.8 * v;
      exact += wt * (w.alpha(0, 0) * wu * wu + 2 * w.alpha(0, 1) * wu * wv + w.alpha(1, 1) * wv * wv +
                     w.beta(0, 0) * wuu * wuu + 2 * w.beta(0, 1) * wuv * wuv + w.beta(1, 1) * wvv * wvv);
    }
  CHECK(0.5 * p.dot(H * p) == Approx(exact).epsilon(1e-9));

  // Null spaces: bending only → {1, u, v} on an open sheet, {1, v} when periodic in u;
  // with tension → constants only. Kraft's selection adds no spurious null vectors.
  TensionWeights bending;  // β all ones: w_uu² + 2w_uv² + w_vv² (β = I would miss w = uv)
  const double tol = 1e-9;
  CHECK(smallest_eigenvalues_count(thin_plate_hessian(s, bending, Backend::Optimized), tol) == 3);
  Eigen::MatrixXd d2;
  const HierarchicalSurface cyl = refined_sheet(&d2, true);
  CHECK(smallest_eigenvalues_count(thin_plate_hessian(cyl, bending, Backend::Optimized), tol) == 2);
  CHECK(smallest_eigenvalues_count(H, tol) == 1);

  TensionWeights bad;
  bad.alpha << 1, 2, 2, 1;  // indefinite
  CHECK_THROWS_AS(thin_plate_hessian(s, bad, Backend::Optimized), InvalidInput);
}

TEST_CASE("B-spline constraints: domain checks and curve rows that reproduce a curve the surface contains", "[bspline]") {
  HierarchicalSurface s({4, 4, 3, false});
  CHECK_THROWS_WITH(point_rows(s, 4.5, 1, Vec3::Zero()), Catch::Contains("outside the parameter domain"));
  CurveAttachment leaving{{{1, 1}, {3, 5}}, {Vec3::Zero(), Vec3::Ones()}, nullptr};
  CHECK_THROWS_WITH(curve_rows(s, leaving, CurveQuadrature::Exact), Catch::Contains("(u, v) point 1"));
  // A surface that contains the space curve satisfies the rows exactly.
  const Eigen::MatrixXd P = random_coefficients(s.dof_count(), 4);
  CurveAttachment c;
  for (int k = 0; k <= 20; ++k) c.uv.emplace_back(0.5 + 0.15 * k, 1.0 + 2.0 * std::sin(0.2 * k) * 0.5);
  c.space = surface_curve(s, P, c.uv, 400);  // densely sampled: piecewise-linear D ≈ the surface curve
  const ConstraintRows rows = curve_rows(s, c, CurveQuadrature::Exact);
  CHECK(rows.A.rows() > 16);
  CHECK((rows.A * P - rows.C).norm() < 1e-3 * rows.C.norm());
}

TEST_CASE("rest shape: installed shapes are kept, melt returns to the remembered one, through refinement", "[bspline]") {
  HierarchicalSurface probe({4, 4, 3, false});
  const Eigen::MatrixXd flat = linear_coefficients(probe);
  VariationalSheet sheet({4, 4, 3, false}, flat);
  sheet.remember_rest_shape();  // the flat sheet
  Eigen::MatrixXd bent = flat;
  bent.col(2) = random_coefficients(probe.dof_count(), 8).col(0);
  sheet.set_coefficients(bent);
  sheet.install_rest_shape();
  CHECK((sheet.rest() - bent).norm() == 0);
  // With eq. 6 and one point held where the rest shape has it, the solution is the rest shape.
  SheetEnergy e;
  e.rest_shape = true;
  e.weights.alpha = 0.1 * Eigen::Matrix2d::Identity();
  SheetConstraint hold;
  hold.u = hold.v = 2;
  hold.target = sheet.surface().position(bent, 2, 2);
  Config none;
  auto kkt = qp::qp_solver_registry().create("kkt", Backend::Optimized, none);
  sheet.refine({{0, 1, 1}});
  DesignReport r = solve_sheet(sheet, e, {hold}, *kkt, {}, Backend::Optimized);
  REQUIRE(r.qp.summary.termination == Termination::Converged);
  CHECK((sheet.surface().position(sheet.coefficients(), 1.3, 0.7) - probe.position(bent, 1.3, 0.7)).norm() < 1e-9);
  sheet.melt();  // back to the flat sheet: the same solve now returns the plane through the held point
  r = solve_sheet(sheet, e, {hold}, *kkt, {}, Backend::Optimized);
  const Vec3 offset = hold.target - Vec3(2, 2, 0);
  CHECK((sheet.surface().position(sheet.coefficients(), 1.3, 0.7) - (Vec3(1.3, 0.7, 0) + offset)).norm() < 1e-9);
}
