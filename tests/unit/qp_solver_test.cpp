// The constrained quadratic solvers (Welch & Witkin §4.3) on B-spline problems.
#include <catch2/catch.hpp>

#include <cmath>

#include "fairshape/bspline/hierarchical_surface.h"
#include "fairshape/bspline/surface_constraints.h"
#include "fairshape/bspline/thin_plate_energy.h"
#include "fairshape/core/config.h"
#include "fairshape/qp/kkt_solver.h"
#include "fairshape/qp/qp_solver.h"
#include "fairshape/qp/qr_penalty_solver.h"
#include "fairshape/qp/range_space_solver.h"
#include "qp_test_programs.h"

using namespace fairshape;
using namespace fairshape::bspline;
using namespace fairshape::qp;
using fairshape::test::SheetProblem;

namespace {

std::unique_ptr<QpSolver> make(const std::string& name, Backend backend, const std::string& yaml = "{}") {
  Config cfg(YAML::Load(yaml), "solver");
  auto solver = qp_solver_registry().create(name, backend, cfg);
  cfg.check_no_unknown_keys();
  return solver;
}

// `base` with its constraint rows replaced.
QuadraticProgram with_rows(const QuadraticProgram& base, const ConstraintRows& rows) {
  QuadraticProgram out = base;
  out.A = rows.A;
  out.b = rows.C;
  return out;
}

// A fresh solver of that name (optimized) on the program.
QpReport solved(const std::string& name, const QuadraticProgram& qp) {
  auto solver = make(name, Backend::Optimized);
  solver->analyze(qp);
  return solver->solve(qp.f, qp.b);
}

}  // namespace

TEST_CASE("KKT: constraints to 1e-10, dependent curve rows dropped and reported, reference equals optimized", "[qp]") {
  SheetProblem pr;
  QpReport reports[2];
  for (const Backend backend : {Backend::Reference, Backend::Optimized}) {
    auto solver = make("kkt", backend);
    solver->analyze(pr.qp);
    QpReport r = solver->solve(pr.qp.f, pr.qp.b);
    REQUIRE(r.summary.termination == Termination::Converged);
    CHECK(r.constraint_residual < 1e-10 * (1 + pr.qp.b.norm()));
    CHECK(r.dropped_rows > 0);  // an isoparametric curve: r+1 independent rows per span
    CHECK(r.summary.message.find("dropped") != std::string::npos);
    reports[backend == Backend::Optimized] = r;
  }
  CHECK((reports[0].p - reports[1].p).norm() <= 1e-8 * reports[1].p.norm());
  // Optimality: the energy gradient lies in the row space of A (KKT stationarity).
  const Eigen::MatrixXd g = pr.qp.H * reports[1].p - pr.qp.f;
  const Eigen::MatrixXd At = Eigen::MatrixXd(SparseMatrix(pr.qp.A.transpose()));
  const Eigen::MatrixXd lambda = At.completeOrthogonalDecomposition().solve(g);
  CHECK((At * lambda - g).norm() < 1e-8 * (1 + g.norm()));
}

TEST_CASE("KKT on a program whose H diagonal spans ten and twenty orders more: the same answer, in its own units", "[qp]") {
  // The sheet's unknowns rescaled by D (10^0 .. 10^-5, a smooth grading across the unknowns): the
  // program min ½ yᵀ(DHD)y − (Df)ᵀy, (AD)y = b is the sheet's in other units, so its answer is
  // D⁻¹p* exactly, while its H diagonal spans 1e10 (1e20) times the sheet's spread, as on the levels of
  // a dense scan with sliver triangles. UMFPACK's own row scaling keeps 10^-5 exact; at 10^-10 the
  // plain Lagrange system looks singular and is solved equilibrated (qp/kkt_solver.cpp).
  const double orders = GENERATE(5.0, 10.0);
  INFO("grading 10^-" << orders);
  SheetProblem pr;
  const Eigen::Index n = pr.qp.H.rows();
  Eigen::VectorXd d(n);
  for (Eigen::Index i = 0; i < n; ++i) d[i] = std::pow(10.0, -orders * static_cast<double>(i) / static_cast<double>(n - 1));
  QuadraticProgram graded = pr.qp;
  graded.H = SparseMatrix(d.asDiagonal() * pr.qp.H * d.asDiagonal());
  graded.K = SparseMatrix();
  graded.f = d.asDiagonal() * pr.qp.f;
  graded.A = SparseMatrix(pr.qp.A * d.asDiagonal());
  const Eigen::VectorXd diag = graded.H.diagonal();
  REQUIRE(diag.maxCoeff() / diag.minCoeff() > 1e8);
  const QpReport exact = solved("kkt", pr.qp);
  REQUIRE(exact.summary.termination == Termination::Converged);
  const Eigen::MatrixXd expected = d.cwiseInverse().asDiagonal() * exact.p;
  for (const Backend backend : {Backend::Reference, Backend::Optimized}) {
    auto solver = make("kkt", backend);
    solver->analyze(graded);
    const QpReport r = solver->solve(graded.f, graded.b);
    INFO(r.summary.message);
    REQUIRE(r.summary.termination == Termination::Converged);
    CHECK((r.summary.message.find("equilibrated") != std::string::npos) == (orders > 5));
    CHECK((d.asDiagonal() * r.p - exact.p).norm() <= 1e-7 * exact.p.norm());
    CHECK((r.p - expected).norm() <= 1e-6 * expected.norm());
  }
}

TEST_CASE("KKT on a clamped chain too stiff for its Lagrange system: the held unknowns eliminated, the closed-form answer", "[qp]") {
  // E = Σ (p_i − 2p_{i+1} + p_{i+2})² over a chain of n unknowns (H = D₂ᵀD₂, the null space the
  // linear sequences), held at one end (p₀ = p₁ = 0: rows of one entry, as a fixed region's)
  // and pulled at the other ((p_{n−2} + p_{n−1})/2 = 1). H's condition grows as n⁴, so at a few
  // thousand unknowns the LU calls the Lagrange system singular even equilibrated; with the held
  // unknowns eliminated H_FF is positive definite (qp/pinned_reduction.h). The exact answer is
  // a discrete cantilever: stationarity makes the second differences s = D₂p linear, ending
  // s_{n−3} = λ/2 and s_{n−4} = 3λ/2, so p follows from s by summing twice and scaling λ.
  const int n = 3000;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i + 2 < n; ++i) {
    const int c[3] = {i, i + 1, i + 2};
    const double w[3] = {1, -2, 1};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) t.emplace_back(c[a], c[b], w[a] * w[b]);
  }
  QuadraticProgram qp;
  qp.H = SparseMatrix(n, n);
  qp.H.setFromTriplets(t.begin(), t.end());
  qp.f = Eigen::MatrixXd::Zero(n, 1);
  const std::vector<Eigen::Triplet<double>> rows = {{0, 0, 1.0}, {1, 1, 1.0}, {2, n - 2, 0.5}, {2, n - 1, 0.5}};
  qp.A = SparseMatrix(3, n);
  qp.A.setFromTriplets(rows.begin(), rows.end());
  qp.b = Eigen::MatrixXd::Zero(3, 1);
  qp.b(2, 0) = 1.0;
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(n);
  for (int i = 0; i + 2 < n; ++i) expected[i + 2] = (0.5 + (n - 3 - i)) + 2 * expected[i + 1] - expected[i];
  expected /= 0.5 * (expected[n - 2] + expected[n - 1]);
  for (const Backend backend : {Backend::Reference, Backend::Optimized}) {
    auto solver = make("kkt", backend);
    solver->analyze(qp);
    const QpReport r = solver->solve(qp.f, qp.b);
    INFO(r.summary.message);
    REQUIRE(r.summary.termination == Termination::Converged);
    CHECK(r.summary.message.find("range-space method") != std::string::npos);
    // H_FF's condition is about 1e13, so a backward-stable solve's error is bounded only by
    // κ·ε ≈ 1e-3; measured 1.5e-6.
    CHECK((r.p.col(0) - expected).norm() <= 1e-5 * expected.norm());
    CHECK(std::abs(0.5 * (r.p(n - 2, 0) + r.p(n - 1, 0)) - 1.0) < 1e-10);
  }
}

TEST_CASE("KKT reuses UMFPACK's symbolic analysis for a program with the same pattern", "[qp]") {
  SheetProblem pr;
  KktSolver solver(Backend::Optimized);
  solver.analyze(pr.qp);
  QuadraticProgram stiffer = pr.qp;
  stiffer.H *= 3.0;
  solver.analyze(stiffer);
  CHECK(solver.symbolic_analyses() == 1);
  const QpReport r = solver.solve(stiffer.f, stiffer.b);
  CHECK(r.constraint_residual < 1e-10 * (1 + pr.qp.b.norm()));
}

TEST_CASE("QR-penalty: each refinement step shrinks the residual and agrees with KKT as mu grows", "[qp]") {
  SheetProblem pr;
  auto kkt = make("kkt", Backend::Optimized);
  kkt->analyze(pr.qp);
  const Eigen::MatrixXd exact = kkt->solve(pr.qp.f, pr.qp.b).p;
  for (const Backend backend : {Backend::Reference, Backend::Optimized}) {
    // μ held at 10 (max_mu): Van Loan's steps alone, each shrinking the residual; converged
    // only if the last one meets constraint_tolerance.
    auto penalty = make("qr_penalty", backend, "{mu: 10, refinement_steps: 4, max_mu: 10}");
    penalty->analyze(pr.qp);
    const QpReport r = penalty->solve(pr.qp.f, pr.qp.b);
    REQUIRE(r.residual_history.size() >= 2);
    REQUIRE(r.residual_history.size() <= 5);
    CHECK((r.summary.termination == Termination::Converged) == (r.residual_history.back() <= 1e-8));
    for (std::size_t k = 1; k < r.residual_history.size(); ++k) CHECK(r.residual_history[k] < r.residual_history[k - 1]);
    INFO("residuals " << r.residual_history[0] << " ... " << r.residual_history.back());
    // Through Q or through R alone: the same answer at a moderate mu.
    auto orthogonal = make("qr_penalty", backend, "{mu: 10, refinement_steps: 4, max_mu: 10, solve: orthogonal}");
    orthogonal->analyze(pr.qp);
    CHECK((orthogonal->solve(pr.qp.f, pr.qp.b).p - r.p).norm() <= 1e-8 * r.p.norm());
    // On the point constraints alone (well conditioned rows), the plain penalty converges to the
    // KKT answer as mu grows.
    QuadraticProgram points = pr.qp;
    points.A = pr.qp.A.topRows(5);
    points.b = pr.qp.b.topRows(5);
    kkt->analyze(points);
    const Eigen::MatrixXd exact_points = kkt->solve(points.f, points.b).p;
    double previous_error = std::numeric_limits<double>::infinity();
    for (const double mu : {1.0, 10.0, 100.0, 1000.0}) {
      auto plain = make("qr_penalty", backend, "{mu: " + std::to_string(mu) + ", refinement_steps: 0}");
      plain->analyze(points);
      const double error = (plain->solve(points.f, points.b).p - exact_points).norm() / exact_points.norm();
      INFO("mu " << mu << " error " << error);
      CHECK(error < previous_error);
      previous_error = error;
    }
    CHECK(previous_error < 1e-4);
  }
}

TEST_CASE("range space: agrees with KKT, and added/removed rows (bordered S, CHOLMOD downdate) give the refactored answer", "[qp]") {
  SheetProblem pr;
  auto kkt = make("kkt", Backend::Optimized);
  kkt->analyze(pr.qp);
  const Eigen::MatrixXd exact = kkt->solve(pr.qp.f, pr.qp.b).p;
  RangeSpaceSolver rs;
  rs.analyze(pr.qp);
  const QpReport r = rs.solve(pr.qp.f, pr.qp.b);
  REQUIRE(r.summary.termination == Termination::Converged);
  CHECK((r.p - exact).norm() < 1e-7 * exact.norm());
  CHECK(r.constraint_residual < 1e-8 * (1 + pr.qp.b.norm()));

  // One more point constraint, by update and by a fresh analysis.
  const ConstraintRows extra = point_rows(pr.s, 1.5, 4.0, Vec3(1.5, 4.0, -0.7));
  rs.add_rows(extra.A);
  const QuadraticProgram bigger = with_rows(pr.qp, stack({{pr.qp.A, pr.qp.b}, extra}, pr.s.dof_count()));
  kkt->analyze(bigger);
  const Eigen::MatrixXd exact2 = kkt->solve(bigger.f, bigger.b).p;
  CHECK((rs.solve(bigger.f, bigger.b).p - exact2).norm() < 1e-7 * exact2.norm());
  // And removed again (a bordered row: S shrinks).
  rs.remove_rows({static_cast<int>(bigger.A.rows()) - 1});
  CHECK((rs.solve(pr.qp.f, pr.qp.b).p - exact).norm() < 1e-7 * exact.norm());
  // Removing an original row downdates the CHOLMOD factor.
  rs.remove_rows({0});
  QuadraticProgram smaller = pr.qp;
  smaller.A = pr.qp.A.bottomRows(pr.qp.A.rows() - 1);
  smaller.b = pr.qp.b.bottomRows(pr.qp.b.rows() - 1);
  kkt->analyze(smaller);
  const Eigen::MatrixXd exact3 = kkt->solve(smaller.f, smaller.b).p;
  CHECK((rs.solve(smaller.f, smaller.b).p - exact3).norm() < 1e-7 * exact3.norm());
}

TEST_CASE("constrained solvers report singular and inconsistent problems instead of returning NaN", "[qp]") {
  SheetProblem pr;
  // A single point constraint leaves the bending null space {1, u, v} unpinned.
  QuadraticProgram loose = pr.qp;
  const ConstraintRows one = point_rows(pr.s, 3, 3, Vec3(0, 0, 1));
  loose.A = one.A;
  loose.b = one.C;
  loose.H = thin_plate_hessian(pr.s, TensionWeights{}, Backend::Optimized);
  loose.K = thin_plate_square_root(pr.s, TensionWeights{});
  for (const std::string name : {"kkt", "qr_penalty"}) {
    auto solver = make(name, Backend::Optimized);
    solver->analyze(loose);
    const QpReport r = solver->solve(loose.f, loose.b);
    INFO(name << ": " << r.summary.message);
    CHECK(r.summary.termination == Termination::NumericalFailure);
    CHECK(r.p.allFinite());
    CHECK(r.summary.message.find("null space") != std::string::npos);
  }
  // A μ far beyond the energy's scale: warned (badly conditioned) or refused (numerically
  // singular), never a silent answer.
  {
    auto huge = make("qr_penalty", Backend::Optimized, "{mu: 1.0e12, refinement_steps: 0}");
    huge->analyze(pr.qp);
    const QpReport r = huge->solve(pr.qp.f, pr.qp.b);
    INFO(r.summary.message);
    CHECK((r.summary.message.find("badly conditioned") != std::string::npos || r.summary.message.find("numerically singular") != std::string::npos));
    CHECK(r.p.allFinite());
  }
  // The same point pulled to two places: least-squares fit with the residual reported.
  const QuadraticProgram inconsistent =
      with_rows(pr.qp, stack({{pr.qp.A, pr.qp.b}, point_rows(pr.s, 3, 3, Vec3(3, 3, -1.5))}, pr.s.dof_count()));
  for (const std::string name : {"kkt", "range_space", "qr_penalty"}) {
    const QpReport r = solved(name, inconsistent);
    INFO(name << ": " << r.summary.message);
    CHECK(r.summary.termination == Termination::ConstraintsUnmet);
    CHECK(r.summary.message.find("not met: relative residual") != std::string::npos);
    CHECK(r.summary.message.find("e-01") != std::string::npos);  // numbers in scientific notation
    if (name != "qr_penalty") CHECK(r.constraint_residual == Approx(3.0 / std::sqrt(2.0)).epsilon(1e-6));  // midway: 1.5 off each way
    CHECK(r.p.allFinite());
  }
}

TEST_CASE("every constrained solver calls nearly coincident points pulled apart ill-conditioned, with the estimate", "[qp]") {
  // Two points 1e-4 spans apart pulled 0.6 up and down: solvable, at an energy 1e8 times the
  // design's (the sheet spans z in [-23, 43]).
  SheetProblem pr;
  // The five point constraints, and points at (1.5, 4) and (1.5, v) pulled up and down.
  const auto pulled_apart = [&](double v) {
    const ConstraintRows pair = stack({point_rows(pr.s, 1.5, 4.0, Vec3(1.5, 4.0, 0.6)), point_rows(pr.s, 1.5, v, Vec3(1.5, v, -0.6))},
                                      pr.s.dof_count());
    return with_rows(pr.qp, stack({{pr.qp.A.topRows(5), pr.qp.b.topRows(5)}, pair}, pr.s.dof_count()));
  };
  const QuadraticProgram pulled = pulled_apart(4.0001), apart = pulled_apart(4.5);
  for (const std::string name : {"kkt", "range_space", "qr_penalty"}) {
    const QpReport r = solved(name, pulled);
    INFO(name << ": " << r.summary.message);
    CHECK(r.summary.termination == Termination::IllConditioned);
    CHECK(r.condition_estimate > 1e7);
    CHECK(r.summary.message.find("condition estimate") != std::string::npos);
    // The same points 0.5 spans apart: well posed, converged, a moderate estimate.
    const QpReport ok = solved(name, apart);
    CHECK(ok.summary.termination == Termination::Converged);
    CHECK(ok.condition_estimate < 1e5);
  }
  // 8e-4 spans apart: badly conditioned but below max_condition, solved by every solver to the
  // same answer (QR-penalty used to run out of refinement steps at its first mu and give up).
  const QuadraticProgram close = pulled_apart(4.0008);
  const QpReport kkt = solved("kkt", close);
  REQUIRE(kkt.summary.termination == Termination::Converged);
  for (const std::string name : {"range_space", "qr_penalty"}) {
    const QpReport r = solved(name, close);
    INFO(name << ": " << r.summary.message);
    CHECK(r.summary.termination == Termination::Converged);
    CHECK((r.p - kkt.p).cwiseAbs().maxCoeff() <= 1e-5 * kkt.p.cwiseAbs().maxCoeff());
  }
}

TEST_CASE("QR-penalty says when it could not meet the constraints: no refinement and no room for mu", "[qp]") {
  SheetProblem pr;
  auto weak = make("qr_penalty", Backend::Optimized, "{mu: 1, refinement_steps: 0, max_mu: 1}");
  weak->analyze(pr.qp);
  const QpReport r = weak->solve(pr.qp.f, pr.qp.b);
  INFO(r.summary.message);
  CHECK(r.summary.termination == Termination::ConstraintsUnmet);
  CHECK(r.summary.message.find("constraint_tolerance") != std::string::npos);
  // With its defaults it refines (and raises mu if it must) until the tolerance is met.
  auto fine = make("qr_penalty", Backend::Optimized);
  fine->analyze(pr.qp);
  const QpReport f = fine->solve(pr.qp.f, pr.qp.b);
  CHECK(f.summary.termination == Termination::Converged);
  CHECK(f.residual_history.back() <= 1e-8);
}

TEST_CASE("the paper's split: feasible, never below the minimizer's energy, the minimizer itself when started there",
          "[qp]") {
  SheetProblem pr;
  auto kkt = make("kkt", Backend::Optimized);
  kkt->analyze(pr.qp);
  const QpReport exact = kkt->solve(pr.qp.f, pr.qp.b);
  REQUIRE(exact.summary.termination == Termination::Converged);
  for (Backend b : {Backend::Reference, Backend::Optimized}) {
    INFO(to_string(b));
    auto split = make("paper", b, "{free_solver: {type: conjugate_gradient, tolerance: 1.0e-13, max_iterations: 100000}}");
    split->analyze(pr.qp);
    const QpReport r = split->solve(pr.qp.f, pr.qp.b);
    REQUIRE(r.summary.succeeded());
    CHECK(r.constraint_residual <= 1e-7 * (1 + pr.qp.b.norm()));
    // Feasible, so no better than the constrained minimizer; the constrained unknowns are not
    // optimized, so on this sheet (positions as unknowns) much worse.
    CHECK(objective(pr.qp, r.p) >= objective(pr.qp, exact.p) - 1e-9 * std::abs(objective(pr.qp, exact.p)));
    // Started at the minimizer with the least change that keeps the rows, it stays there.
    QpSolveOptions from_exact;
    from_exact.initial = &exact.p;
    from_exact.nearest_to_initial = true;
    const QpReport again = split->solve(pr.qp.f, pr.qp.b, from_exact);
    CHECK((again.p - exact.p).norm() <= 1e-6 * exact.p.norm());
  }
  CHECK_THROWS_WITH(make("paper", Backend::Optimized, "{free_solver: {type: lu}}"), Catch::Matchers::Contains("valid:"));
}
