// The variational curve's hierarchical B-spline basis and its refinement by constraint error
// (Welch & Witkin's curves as 1-D hierarchical B-splines), alone and joined to sheets.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include <Eigen/QR>

#include "fairshape/bspline/hierarchical_curve_basis.h"
#include "fairshape/bspline/joined_design.h"
#include "fairshape/bspline/variational_curve.h"
#include "fairshape/core/config.h"
#include "fairshape/core/error.h"
#include "fairshape/qp/qp_solver.h"
#include "sheet_test_support.h"

using namespace fairshape;
using namespace fairshape::bspline;

namespace {

std::unique_ptr<qp::QpSolver> make_solver(const std::string& name) {
  Config none;
  return qp::qp_solver_registry().create(name, Backend::Optimized, none);
}

// The curve's basis functions at many points, as a dense matrix (points × dofs).
Eigen::MatrixXd basis_values(const HierarchicalCurveBasis& b, int points) {
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(points, b.knot_basis().size());
  std::vector<double> v;
  int first = 0;
  for (int p = 0; p < points; ++p) {
    b.knot_basis().evaluate((p + 0.5) / points, first, v);
    for (std::size_t i = 0; i < v.size(); ++i) N(p, first + static_cast<int>(i)) = v[i];
  }
  return N * Eigen::MatrixXd(b.to_knot_basis());
}

// A basis refined at random leaves, three rounds deep.
HierarchicalCurveBasis randomly_refined(int spans, int degree, unsigned seed) {
  HierarchicalCurveBasis b(spans, degree);
  std::mt19937 gen(seed);
  for (int round = 0; round < 3; ++round) {
    std::vector<CurveSpan> pick;
    for (const CurveSpan& leaf : b.leaf_cells())
      if (gen() % 3 == 0) pick.push_back(leaf);
    b.refine(pick);
  }
  return b;
}

}  // namespace

TEST_CASE("hierarchical curve basis: one B-spline on its own knots matches the clamped basis", "[bspline][free_curve]") {
  for (int r = 2; r <= 5; ++r) {
    const ClampedKnotBasis clamped(0, 1, {0.2, 0.45, 0.5, 0.8}, r);
    std::vector<double> U(static_cast<std::size_t>(r + 1), 0.0);
    for (double k : {0.2, 0.45, 0.5, 0.8}) U.push_back(k);
    U.insert(U.end(), static_cast<std::size_t>(r + 1), 1.0);
    for (double x : {0.05, 0.3, 0.47, 0.66, 0.93}) {
      int first = 0;
      std::vector<double> v;
      clamped.evaluate(x, first, v);
      for (std::size_t i = 0; i < v.size(); ++i) {
        const std::size_t j = static_cast<std::size_t>(first) + i;
        const std::vector<double> own(U.begin() + static_cast<long>(j), U.begin() + static_cast<long>(j) + r + 2);
        CHECK(single_bspline(own, x) == Approx(v[i]).margin(1e-14));
      }
    }
  }
}

TEST_CASE("hierarchical curve basis: linearly independent, local, and nested under refinement", "[bspline][free_curve]") {
  for (int degree : {2, 3, 5})
    for (unsigned seed : {1u, 2u, 3u}) {
      const HierarchicalCurveBasis b = randomly_refined(5, degree, seed);
      INFO("degree " << degree << ", seed " << seed << ": " << b.level_count() << " layers, " << b.dof_count() << " functions");
      // Kraft's selection: independent functions (full column rank at enough points).
      const Eigen::MatrixXd N = basis_values(b, 40 * static_cast<int>(b.leaf_cells().size()));
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(N);
      qr.setThreshold(1e-10);
      CHECK(qr.rank() == b.dof_count());
      // The leaves tile [0, 1].
      double t = 0;
      for (const CurveSpan& leaf : b.leaf_cells()) {
        CHECK(leaf.t0 == t);
        t = leaf.t1;
      }
      CHECK(t == 1);
      // The refined space contains the coarse one: the base basis is reproduced exactly.
      const HierarchicalCurveBasis base(5, degree);
      const Eigen::MatrixXd N0 = basis_values(base, N.rows());
      const Eigen::MatrixXd coefficients = qr.solve(N0);
      CHECK((N * coefficients - N0).cwiseAbs().maxCoeff() < 1e-11);
    }
  // Locality: refining the middle leaf of 16 touches leaves within r + 1 base spans only.
  HierarchicalCurveBasis b(16, 3);
  b.refine({b.leaf_cell_at(0.5)});
  for (const CurveSpan& leaf : b.leaf_cells())
    if (leaf.level > 0) CHECK(std::abs(0.5 * (leaf.t0 + leaf.t1) - 0.53125) < 4.0 / 16);
  CHECK(b.level_count() == 2);
  CHECK(b.leaf_cells().size() > 16);
  CHECK_THROWS_WITH(b.refine({CurveSpan{0, 8, 0.5, 0.5625}}), Catch::Matchers::Contains("is not a leaf cell"));
}

TEST_CASE("variational curve: refinement keeps the curve and its energy, and polynomials stay exact", "[bspline][free_curve]") {
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> d(-1, 1);
  CurveEnergy e;
  e.alpha = 0.2;
  e.beta = 0.01;
  for (int degree : {2, 3, 4}) {
    Eigen::MatrixXd q(6 + degree, 3);
    for (Eigen::Index i = 0; i < q.size(); ++i) q.data()[i] = d(gen);
    VariationalCurve c({6, degree}, q, 1.7);
    const VariationalCurve before = c;
    const double energy = curve_energy(c, e);
    std::vector<CurveSpan> leaves{c.basis().leaf_cells()[0], c.basis().leaf_cells()[3]};
    CHECK(c.refine(leaves) > 0);
    CHECK(c.refine({c.basis().leaf_cell_at(0.51)}) > 0);
    CHECK(c.basis().level_count() == 3);
    CHECK(c.dof_count() > before.dof_count());
    for (double t = 0; t <= 1; t += 1.0 / 97) {
      CHECK((c.position(t) - before.position(t)).norm() < 1e-11);
      CHECK((c.tangent(t) - before.tangent(t)).norm() < 1e-9);
    }
    // The energy integrates the same curve on finer cells: the same number.
    CHECK(curve_energy(c, e) == Approx(energy).epsilon(1e-10));
  }
}

TEST_CASE("variational curve alone: refinement by constraint error meets what a coarse curve cannot, locally", "[bspline][free_curve]") {
  // Nine points of a wiggle packed into t ∈ [0.4, 0.6] of a 4-span cubic curve (7 functions):
  // no coarse curve passes through them (constraints_unmet); refining where they miss adds
  // functions there only, until every point is met.
  CurveEnergy e;
  e.alpha = 0;
  e.beta = 1;
  VariationalCurve c({4, 3}, std::vector<Vec3>{Vec3(0, 0, 0), Vec3(4, 0, 0)});
  JoinedCurve jc;
  jc.curve = &c;
  jc.energy = e;
  for (double t : {0.0, 1.0}) jc.constraints.push_back({CurveConstraint::Kind::Point, t, Vec3(4 * t, 0, 0), "end"});
  for (int k = 0; k < 9; ++k) {
    const double t = 0.4 + 0.025 * k;
    jc.constraints.push_back({CurveConstraint::Kind::Point, t, Vec3(4 * t, 0.05 * std::sin(k * 1.7), 0), "wiggle"});
  }
  SECTION("without refinement the error is reported, not hidden") {
    JoinedDesign d;
    d.curves = {jc};
    auto kkt = make_solver("kkt");
    const JoinedReport r = solve_joined(d, *kkt, Backend::Optimized);
    CHECK(r.qp.summary.termination == Termination::ConstraintsUnmet);
    CHECK(r.curve_error[0] > 1e-3);
  }
  // A fresh 4-span curve with those constraints, solved by `solver` refining to 1e-8 up to max_level.
  const auto refined_solve = [&](VariationalCurve& fresh, const std::string& solver, int max_level) {
    JoinedDesign d;
    d.curves = {jc};
    d.curves[0].curve = &fresh;
    RefinementOptions refinement;
    refinement.tolerance = 1e-8;
    refinement.max_level = max_level;
    return solve_joined(d, *make_solver(solver), Backend::Optimized, refinement);
  };
  SECTION("with refinement every solver meets the points, refining only near them") {
    std::vector<double> energies;
    for (const std::string name : {"kkt", "range_space", "qr_penalty"}) {
      VariationalCurve fresh({4, 3}, std::vector<Vec3>{Vec3(0, 0, 0), Vec3(4, 0, 0)});
      const JoinedReport r = refined_solve(fresh, name, 6);
      INFO(name << ": " << r.message);
      REQUIRE(r.qp.summary.termination == Termination::Converged);
      CHECK(r.rounds > 1);
      CHECK(r.curve_spans_refined[0] > 0);
      CHECK(r.curve_error[0] < 1e-8);
      // Graded: the deepest layer only around the points, the ends coarser.
      const int deepest = fresh.basis().level_count() - 1;
      CHECK(deepest >= 2);
      for (const CurveSpan& leaf : fresh.basis().leaf_cells())
        if (leaf.level == deepest) CHECK((leaf.t0 >= 0.25 && leaf.t1 <= 0.75));
      CHECK(fresh.basis().leaf_cell_at(0).level < deepest);
      CHECK(fresh.basis().leaf_cell_at(1).level < deepest);
      energies.push_back(r.energy());
    }
    CHECK(energies[1] == Approx(energies[0]).epsilon(1e-6));
    CHECK(energies[2] == Approx(energies[0]).epsilon(1e-6));
  }
  SECTION("a tolerance the depth cannot reach ends constraints_unmet, saying so") {
    VariationalCurve fresh({4, 3}, std::vector<Vec3>{Vec3(0, 0, 0), Vec3(4, 0, 0)});
    const JoinedReport r = refined_solve(fresh, "kkt", 1);
    CHECK(r.qp.summary.termination == Termination::ConstraintsUnmet);
    CHECK_THAT(r.message, Catch::Matchers::Contains("above the refinement tolerance 1.00e-08 at the maximum depth 1"));
  }
}
