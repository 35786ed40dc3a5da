// Every registered curve energy and length solver (curve_components()), each back end: the
// properties the curve editor of Sauvage, Hahmann and Bonneau (§3) relies on, taken from the
// registries so a component is tested the day it is registered.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>

#include "fairshape/core/config.h"
#include "fairshape/curve_design/curve_components.h"
#include "fairshape/curve_design/length_problem.h"

using namespace fairshape;

namespace {

MatrixX3 random_points(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  MatrixX3 X(n, 3);
  for (int i = 0; i < n; ++i) X.row(i) << u(rng), u(rng), u(rng);
  return X;
}

// ½ Σ_c X_cᵀ H X_c − Σ_c b_cᵀ X_c: the quadratic form the solvers assemble from the stencils.
double quadratic_form(const SparseMatrix& H, const MatrixX3& b, const MatrixX3& X) {
  return 0.5 * (X.transpose() * (H * X)).trace() - (b.transpose() * X).trace();
}

// A gently wavy open curve of n points, about 3 long.
MatrixX3 wave(int n) {
  MatrixX3 X(n, 3);
  for (int i = 0; i < n; ++i) {
    const double t = 3.0 * i / (n - 1);
    X.row(i) << t, 0.3 * std::sin(2.1 * t), 0.1 * std::cos(1.3 * t);
  }
  return X;
}

}  // namespace

TEST_CASE("every curve energy: valid stencils, one quadratic form, positive semidefinite, back ends alike",
          "[conformance][curve]") {
  const CurveEnergyRegistry& reg = curve_components().energies;
  REQUIRE(!reg.names().empty());
  std::mt19937 rng(7);
  for (const auto& entry : reg.entries()) {
    Config none;
    const auto energy = reg.create(entry.name, entry.backend, none);
    none.check_no_unknown_keys();
    for (const bool closed : {false, true})
      for (const int n : {5, 17}) {
        INFO(entry.name << " (" << to_string(entry.backend) << "), " << n << " points, " << (closed ? "closed" : "open"));
        const std::vector<CurveStencil> stencils = energy->stencils(n, closed);
        REQUIRE(!stencils.empty());
        for (const CurveStencil& s : stencils) {
          REQUIRE((s.size >= 1 && s.size <= 3));
          for (int k = 0; k < s.size; ++k) {
            CHECK((s.points[k] >= 0 && s.points[k] < n));
            CHECK(std::isfinite(s.coeffs[k]));
          }
          CHECK((s.attractor_point >= -1 && s.attractor_point < n));
        }
        // The energy is the quadratic form its H and b describe, up to a constant: the
        // difference is the same at any three points.
        const MatrixX3 A = random_points(n, rng);
        const SparseMatrix H = stencil_hessian(stencils, n);
        const MatrixX3 b = stencil_linear_term(stencils, A);
        double constant = 0;
        for (int trial = 0; trial < 3; ++trial) {
          const MatrixX3 X = random_points(n, rng);
          const double gap = stencil_energy(stencils, X, A) - quadratic_form(H, b, X);
          if (trial == 0) constant = gap;
          CHECK(gap == Approx(constant).margin(1e-10 * (1 + std::abs(constant))));
        }
        const Eigen::MatrixXd dense(H);
        CHECK((dense - dense.transpose()).norm() <= 1e-14 * (1 + dense.norm()));
        CHECK(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense).eigenvalues().minCoeff() >= -1e-12 * (1 + dense.norm()));
        // The other back end, where one is registered, describes the same energy.
        const Backend other = entry.backend == Backend::Reference ? Backend::Optimized : Backend::Reference;
        if (reg.has(entry.name, other)) {
          Config none2;
          const SparseMatrix H2 = stencil_hessian(reg.create(entry.name, other, none2)->stencils(n, closed), n);
          CHECK((Eigen::MatrixXd(H2) - dense).norm() <= 1e-14 * (1 + dense.norm()));
        }
      }
  }
}

TEST_CASE("every length solver: a success it reports is one measured on its answer, and the minimizers agree",
          "[conformance][curve]") {
  // Bending + the attractor D (β = 0.5), the segment lengths of a wave kept while the attracting
  // curve is the wave stretched to 103 % of its chord, solved from the wave itself (the lengths
  // met at the start, as after the paper's explicit step): a taut curve, one minimum nearby (a
  // compressed one buckles, and which wrinkle a solver ends in is its own choice).
  const int n = 24;
  const MatrixX3 reference = wave(n);
  MatrixX3 attractor = reference;
  for (int i = 0; i < n; ++i) attractor(i, 0) = reference(i, 0) * (1 + 0.03 * i / (n - 1.0));
  const Eigen::VectorXd lengths = segment_lengths(reference, false);
  const auto problem = [&] {
    std::vector<CurveStencil> pull;
    for (int i = 0; i < n; ++i) pull.push_back({1, {i, 0, 0}, {1.0, 0, 0}, i});
    std::vector<WeightedStencils> energies{{"bending", 0.5, bending_stencils(n, false)}, {"attractor", 0.5, pull}};
    std::vector<std::unique_ptr<CurveConstraint>> constraints;
    constraints.push_back(std::make_unique<SegmentLengths>(lengths, false));
    return LengthProblem(attractor, false, std::move(energies), std::move(constraints), lengths);
  }();

  const LengthSolverRegistry& reg = curve_components().solvers;
  REQUIRE(!reg.names().empty());
  double best = std::numeric_limits<double>::infinity();
  std::vector<std::pair<std::string, double>> minimizers;  // converged solvers' objectives
  for (const auto& entry : reg.entries()) {
    INFO(entry.name << " (" << to_string(entry.backend) << ")");
    Config none;
    const auto solver = reg.create(entry.name, entry.backend, none);
    const LengthSolveReport r = solver->solve(problem, reference);
    INFO(to_string(r.summary.termination) << ": " << r.summary.message);
    REQUIRE(r.points.rows() == n);
    CHECK(r.points.allFinite());
    // The report's own numbers are the answer's.
    CHECK(r.length_error == Approx(problem.max_relative_length_error(r.points)).margin(1e-12));
    if (!is_success(r.summary.termination)) {
      CHECK(!r.summary.message.empty());  // a failure says why
      continue;
    }
    // Success: the lengths are met to the solver's own tolerance (with the rounding floor's
    // room), measured here rather than taken from the report.
    CHECK(problem.max_relative_length_error(r.points) <= 10 * solver->tolerances().length + 1e-12);
    if (r.summary.termination == Termination::Converged && solver->tolerances().stationarity > 0) {
      CHECK(problem.stationarity(r.points) <= 100 * solver->tolerances().stationarity);
      const double f = problem.objective(r.points);
      minimizers.emplace_back(entry.name + " " + std::string(to_string(entry.backend)), f);
      best = std::min(best, f);
    }
  }
  REQUIRE(minimizers.size() >= 2);  // at least the paper's method and the exact one converge here
  for (const auto& [name, f] : minimizers) {
    INFO(name << ": objective " << f << " against the best " << best);
    CHECK(f <= best + 1e-6 * std::abs(best) + 1e-12);
  }
}
