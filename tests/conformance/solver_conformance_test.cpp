// Every registered solver, on both back ends, converges to the direct solution of the same
// systems; the optimized back end is deterministic, whatever the thread count.
#include <catch2/catch.hpp>
#include <tbb/global_control.h>

#include <Eigen/SparseCholesky>
#include <random>

#include "fairshape/energy/laplacian.h"
#include "fairshape/experiment/components.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/problem/constrained_system.h"
#include "fairshape/solver/graph_coloring.h"
#include "test_support.h"
#include "tolerances.h"

using namespace fairshape;

namespace {

struct TestSystem {
  std::string name;
  ReducedSystem r;
};

// Membrane on a triangulated grid with its boundary fixed to a random height field, and a
// random sparse SPD matrix (graph Laplacian of a random graph plus a diagonal shift).
std::vector<TestSystem> systems() {
  std::vector<TestSystem> out;
  const SurfaceMesh m = test::grid(16, true);
  ConstrainedSystem s;
  s.H = -graph_laplacian(m, LaplacianWeights::Uniform);
  s.g = Eigen::MatrixXd::Zero(m.n_vertices(), 3);
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const auto& loop : m.boundary_loops())
    for (int v : loop) s.fixed.push_back(v);
  s.fixed_values.resize(static_cast<Eigen::Index>(s.fixed.size()), 3);
  for (Eigen::Index i = 0; i < s.fixed_values.size(); ++i) s.fixed_values.data()[i] = u(gen);
  out.push_back({"grid membrane", reduce(s)});

  const int n = 300;
  Triplets t;
  for (int k = 0; k < 4 * n; ++k) {
    const int i = static_cast<int>(gen() % n), j = static_cast<int>(gen() % n);
    if (i == j) continue;
    const double w = 0.5 + 0.5 * u(gen);
    t.insert(t.end(), {{i, j, -w}, {j, i, -w}, {i, i, w}, {j, j, w}});
  }
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, 0.05);
  ReducedSystem r;
  r.A.resize(n, n);
  r.A.setFromTriplets(t.begin(), t.end());
  r.b = Eigen::MatrixXd::NullaryExpr(n, 3, [&] { return u(gen); });
  for (int i = 0; i < n; ++i) r.free.push_back(i);
  r.n_full = n;
  out.push_back({"random SPD", r});
  return out;
}

Eigen::MatrixXd direct_solution(const ReducedSystem& r) {
  const Eigen::SimplicialLDLT<SparseMatrix> ldlt(r.A);
  return ldlt.solve(r.b);
}

std::unique_ptr<Solver> make(const std::string& name, Backend b) {
  Config cfg(YAML::Load("{tolerance: 1.0e-12, max_iterations: 200000, sor: {omega: 1.7}}"), "solver");
  return components().solvers.create(name, b, cfg);
}

}  // namespace

TEST_CASE("every solver and back end converges to the direct solution", "[solver][conformance]") {
  for (const auto& sys : systems()) {
    const Eigen::MatrixXd exact = direct_solution(sys.r);
    for (const auto& name : components().solvers.names()) {
      Eigen::MatrixXd by_backend[2];
      for (Backend b : {Backend::Reference, Backend::Optimized}) {
        if (!components().solvers.has(name, b)) continue;
        INFO(sys.name << " / " << name << " / " << to_string(b));
        auto solver = make(name, b);
        if (solver->uses_levels()) continue;  // multilevel solvers: tests/unit/multigrid_test.cpp
        Eigen::MatrixXd x = Eigen::MatrixXd::Zero(sys.r.A.rows(), 3);
        solver->analyze(sys.r.A);
        const SolveSummary s = solver->solve(sys.r.A, sys.r.b, x);
        INFO(s.message);
        REQUIRE(s.termination == Termination::Converged);
        CHECK(s.residual <= test::kSolveResidual * 10);
        const double tol = name == "cholesky" ? test::kDirectAgreement : test::kSolutionAgreement;
        CHECK((x - exact).norm() <= tol * exact.norm());
        by_backend[static_cast<int>(b)] = x;
      }
      if (by_backend[0].size() && by_backend[1].size())
        CHECK((by_backend[0] - by_backend[1]).norm() <= test::kSolutionAgreement * exact.norm());
    }
  }
}

TEST_CASE("warm start from the solution converges at once", "[solver][conformance]") {
  const auto sys = systems().front();
  const Eigen::MatrixXd exact = direct_solution(sys.r);
  for (const auto& name : {"gauss_seidel", "sor", "conjugate_gradient"})
    for (Backend b : {Backend::Reference, Backend::Optimized}) {
      Config cfg(YAML::Load("{tolerance: 1.0e-8}"), "solver");
      auto s = components().solvers.create(name, b, cfg);
      Eigen::MatrixXd x = exact;
      s->analyze(sys.r.A);
      CHECK(s->solve(sys.r.A, sys.r.b, x).iterations == 0);
    }
}

TEST_CASE("multicolour classes are independent sets covering every row once", "[solver]") {
  const auto sys = systems().back();
  const RowSparseMatrix A = sys.r.A;
  const auto classes = color_rows(A);
  std::vector<int> color(A.rows(), -1);
  for (std::size_t c = 0; c < classes.size(); ++c)
    for (int i : classes[c]) {
      REQUIRE(color[i] == -1);
      color[i] = static_cast<int>(c);
    }
  for (int i = 0; i < A.rows(); ++i) {
    REQUIRE(color[i] >= 0);
    for (RowSparseMatrix::InnerIterator it(A, i); it; ++it)
      if (it.col() != i) CHECK(color[it.col()] != color[i]);
  }
}

TEST_CASE("optimized iterative solvers give bit-identical results for 1 and 2 threads", "[solver][determinism]") {
  const auto sys = systems().back();
  for (const auto& name : {"gauss_seidel", "sor", "conjugate_gradient"}) {
    Eigen::MatrixXd x[2];
    for (int threads : {1, 2}) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      auto s = make(name, Backend::Optimized);
      x[threads - 1] = Eigen::MatrixXd::Zero(sys.r.A.rows(), 3);
      s->analyze(sys.r.A);
      s->solve(sys.r.A, sys.r.b, x[threads - 1]);
    }
    INFO(name);
    CHECK((x[0].array() == x[1].array()).all());
  }
}

TEST_CASE("an indefinite system is a numerical failure with a message, never NaN", "[solver]") {
  SparseMatrix A(5, 5);
  A.setIdentity();
  A = -A;
  const Eigen::MatrixXd b = Eigen::MatrixXd::Ones(5, 3);
  for (const auto& name : components().solvers.names())
    for (Backend backend : {Backend::Reference, Backend::Optimized}) {
      if (!components().solvers.has(name, backend)) continue;
      INFO(name << " " << to_string(backend));
      auto s = make(name, backend);
      if (s->uses_levels()) continue;  // needs a hierarchy: tests/unit/multigrid_test.cpp
      Eigen::MatrixXd x = Eigen::MatrixXd::Zero(5, 3);
      s->analyze(A);
      const SolveSummary sum = s->solve(A, b, x);
      CHECK(sum.termination == Termination::NumericalFailure);
      CHECK_FALSE(sum.message.empty());
      CHECK(x.allFinite());
    }
}

TEST_CASE("stopping rules: a fixed sweep count, and the energy rule on a monotone energy", "[solver][stopping]") {
  const auto sys = systems().front();
  for (const auto& name : {"gauss_seidel", "sor", "conjugate_gradient"})
    for (Backend b : {Backend::Reference, Backend::Optimized}) {
      INFO(name << " / " << to_string(b));
      {  // The paper's rule: both tolerances off, exactly max_iterations sweeps.
        Config cfg(YAML::Load("{tolerance: 0, energy_tolerance: 0, max_iterations: 7}"), "solver");
        auto s = components().solvers.create(name, b, cfg);
        Eigen::MatrixXd x = Eigen::MatrixXd::Zero(sys.r.A.rows(), 3);
        const SolveSummary sum = s->solve(sys.r.A, sys.r.b, x);
        CHECK(sum.termination == Termination::ScheduleCompleted);
        CHECK(sum.iterations == 7);
      }
      Config cfg(YAML::Load("{tolerance: 0, energy_tolerance: 1.0e-6, max_iterations: 100000}"), "solver");
      auto s = components().solvers.create(name, b, cfg);
      Eigen::MatrixXd x = Eigen::MatrixXd::Zero(sys.r.A.rows(), 3);
      std::vector<double> energies;
      const SolveSummary sum = s->solve(sys.r.A, sys.r.b, x, [&](const IterationRecord& r) {
        energies.push_back(r.energy);
        return true;
      });
      CHECK(sum.termination == Termination::EnergyStalled);
      REQUIRE(energies.size() >= 3);
      // Gauss-Seidel, SOR (0 < ω < 2) and CG all decrease ½xᵀAx − bᵀx at every step on an SPD system.
      for (std::size_t k = 1; k < energies.size(); ++k) CHECK(energies[k] <= energies[k - 1] + 1e-12 * std::abs(energies[0]));
      const double last_drop = energies[energies.size() - 2] - energies.back();
      CHECK(last_drop <= 1e-6 * (energies.front() - energies.back()));
      // The stationary value is the minimum of the quadratic.
      const Eigen::MatrixXd exact = direct_solution(sys.r);
      const double e_min = 0.5 * exact.cwiseProduct(sys.r.A * exact).sum() - exact.cwiseProduct(sys.r.b).sum();
      CHECK(energies.back() - e_min <= 1e-4 * std::abs(energies.front() - e_min));
    }
}

TEST_CASE("CHOLMOD does not start a factor larger than the memory it may use, and says both sizes",
          "[solver][conformance]") {
  const ReducedSystem r = systems().front().r;
  const auto cholesky = [](const std::string& options) {
    Config cfg(YAML::Load(options), "solver");
    return components().solvers.create("cholesky", Backend::Optimized, cfg);
  };
  SECTION("a limit below the factor's size: out_of_memory, the start left as it was") {
    auto s = cholesky("{cholesky: {memory_limit_mb: 0.0001}}");
    s->analyze(r.A);
    Eigen::MatrixXd x = Eigen::MatrixXd::Constant(r.A.rows(), 3, 7.0);
    const SolveSummary summary = s->solve(r.A, r.b, x);
    CHECK(summary.termination == Termination::OutOfMemory);
    CHECK_THAT(summary.message, Catch::Contains("needs") && Catch::Contains("solver.cholesky.memory_limit_mb"));
    CHECK((x.array() == 7.0).all());
  }
  SECTION("a limit above it, or the machine's memory: factored and solved, the factor's size said") {
    for (const char* options : {"{cholesky: {memory_limit_mb: 100000}}", "{}"}) {
      auto s = cholesky(options);
      Eigen::MatrixXd x = Eigen::MatrixXd::Zero(r.A.rows(), 3);
      const SolveSummary summary = s->solve(r.A, r.b, x);
      CHECK(summary.termination == Termination::Converged);
      CHECK_THAT(summary.message, Catch::Contains("CHOLMOD factor"));
      CHECK(relative_residual(r.A, r.b, x) < 1e-12);
    }
  }
  SECTION("a negative limit is refused by name") {
    CHECK_THROWS_WITH(cholesky("{cholesky: {memory_limit_mb: -1}}"), Catch::Contains("solver.cholesky.memory_limit_mb"));
  }
}
