// The petsc_* solvers (solver/petsc_solver.cpp): on a fourth-order system over a Catmull-Clark
// hierarchy each converges to the direct solution under both back-end names, stops on the true
// residual fairshape's solvers stop on, keeps fairshape's iteration callback, and refuses what it
// cannot honour (options PETSc never read, a missing hierarchy), and stops on the error estimate
// when asked (the Hestenes-Stiefel estimate formed from the iterates). The
// distributed path (petsc.ranks > 1) is tested with mpirun by tests/cli/petsc_mpi.sh.
#include <catch2/catch.hpp>

#include <Eigen/SparseCholesky>

#include <random>
#include <sstream>

#include "fairshape/core/error.h"
#include "fairshape/energy/laplacian.h"
#include "fairshape/experiment/components.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/problem/constrained_system.h"
#include "fairshape/solver/level_operators.h"
#include "fairshape/subdivision/multires_surface.h"
#include "fairshape/subdivision/subdivider.h"
#include "test_support.h"

using namespace fairshape;

namespace {

struct TestSystem {
  ReducedSystem reduced;
  std::shared_ptr<LevelOperators> ops = std::make_shared<LevelOperators>();
};

// The umbrella operator squared (a bi-Laplacian) on the finest of `levels` Catmull-Clark steps
// of the double torus, a band of vertices pinned to random values.
const TestSystem& bilaplacian_system() {
  static const TestSystem t = [] {
    const int levels = 2;
    const MultiresSurface h(read_mesh(test::data_path("double-torus-example.off")), SubdivisionOptions{}, levels,
                            Backend::Optimized);
    const SurfaceMesh& f = h.mesh(levels);
    const SparseMatrix U = umbrella_operator(f);
    ConstrainedSystem s{SparseMatrix(U.transpose()) * U, Eigen::MatrixXd::Zero(f.n_vertices(), 3), {}, {}};
    const double lo = f.positions().col(0).minCoeff(), hi = f.positions().col(0).maxCoeff();
    for (int v = 0; v < f.n_vertices(); ++v)
      if (f.positions()(v, 0) < lo + 0.2 * (hi - lo)) s.fixed.push_back(v);
    s.fixed_values.resize(static_cast<Eigen::Index>(s.fixed.size()), 3);
    std::mt19937 gen(3);
    std::uniform_real_distribution<double> u(-1, 1);
    for (Eigen::Index i = 0; i < s.fixed_values.size(); ++i) s.fixed_values.data()[i] = u(gen);
    TestSystem out{reduce(s)};
    for (int l = 0; l < levels; ++l) out.ops->prolongation.push_back(h.subdivision_operator(l));
    for (int l = 0; l <= levels; ++l) out.ops->singular.push_back(extraordinary_vertices(h.mesh(l), SchemeType::CatmullClark));
    out.ops->positions = f.positions();
    return out;
  }();
  return t;
}

std::unique_ptr<Solver> make(const std::string& name, Backend backend, const std::string& options) {
  Config cfg(YAML::Load(options), "solver");
  auto s = components().solvers.create(name, backend, cfg);
  cfg.check_no_unknown_keys();
  const TestSystem& t = bilaplacian_system();
  if (s->uses_levels()) s->set_levels(t.ops, {t.reduced.free, 1});
  return s;
}


const Eigen::MatrixXd& exact_solution() {
  static const Eigen::MatrixXd x = Eigen::SimplicialLDLT<SparseMatrix>(bilaplacian_system().reduced.A).solve(bilaplacian_system().reduced.b);
  return x;
}

const char* const kPetscSolvers[] = {"petsc_mg", "petsc_gamg", "petsc_boomeramg"};

}  // namespace

TEST_CASE("petsc solvers converge to the direct solution of a fourth-order system, on both back-end names",
          "[solver][petsc]") {
  const TestSystem& t = bilaplacian_system();
  for (const char* name : kPetscSolvers)
    for (Backend backend : {Backend::Reference, Backend::Optimized}) {
      REQUIRE(components().solvers.has(name, backend));
      auto s = make(name, backend, "{tolerance: 1.0e-12, max_iterations: 5000}");
      Eigen::MatrixXd x = Eigen::MatrixXd::Zero(t.reduced.A.rows(), 3);
      int calls = 0;
      const SolveSummary sum = s->solve(t.reduced.A, t.reduced.b, x, [&](const IterationRecord&) { return ++calls > 0; });
      INFO(name << " / " << to_string(backend) << ": " << sum.message);
      CHECK(sum.termination == Termination::Converged);
      // The summary's residual is recomputed from A, not PETSc's recursive one.
      CHECK(sum.residual == Approx((t.reduced.b - t.reduced.A * x).norm() / t.reduced.b.norm()).epsilon(1e-6));
      CHECK(sum.residual <= 1e-11);
      CHECK(relative_error(x, exact_solution()) < 1e-7);
      CHECK(calls >= sum.iterations);  // every column's iterations reach the callback
    }
}

TEST_CASE("petsc solvers stop on the error estimate and the true error is near the one asked", "[solver][petsc]") {
  // As fairshape's own CG solvers (multigrid_test): the estimate is a lower bound of the A-norm
  // error `error_delay` iterations back, so the returned (later) iterate is within a small
  // factor of the asked error.
  const TestSystem& t = bilaplacian_system();
  const Eigen::MatrixXd& exact = exact_solution();
  const auto a_norm_error = [&](const Eigen::MatrixXd& x) {
    const Eigen::MatrixXd e = x - exact;
    return std::sqrt((e.transpose() * (t.reduced.A * e)).trace() / (exact.transpose() * (t.reduced.A * exact)).trace());
  };
  for (const char* name : kPetscSolvers)
    for (double asked : {1e-4, 1e-7}) {
      std::ostringstream options;
      options << "{error_tolerance: " << asked << ", max_iterations: 5000}";
      auto s = make(name, Backend::Optimized, options.str());
      Eigen::MatrixXd x = Eigen::MatrixXd::Zero(t.reduced.A.rows(), 3);
      const SolveSummary sum = s->solve(t.reduced.A, t.reduced.b, x);
      INFO(name << " asked " << asked << ": " << sum.iterations << " iterations, " << sum.message);
      REQUIRE(sum.termination == Termination::Converged);
      CHECK(sum.error_estimate >= 0);
      CHECK(sum.error_estimate <= asked);
      CHECK(a_norm_error(x) < 10 * asked);
      CHECK_THAT(sum.message, Catch::Contains("error estimate"));
    }
  // The cap before the error tolerance is not convergence, and says so.
  auto capped = make("petsc_mg", Backend::Optimized, "{error_tolerance: 1.0e-12, max_iterations: 3}");
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(t.reduced.A.rows(), 3);
  const SolveSummary sum = capped->solve(t.reduced.A, t.reduced.b, x);
  CHECK(sum.termination == Termination::MaxIterations);
  CHECK_THAT(sum.message, Catch::Contains("error tolerance"));
}

TEST_CASE("petsc_mg over fairshape's prolongations needs far fewer iterations than one-level CG", "[solver][petsc]") {
  // A hierarchy that did nothing would leave petsc_mg near a one-level preconditioner's count.
  const TestSystem& t = bilaplacian_system();
  const auto iterations = [&](const std::string& name) {
    auto s = make(name, Backend::Optimized, "{tolerance: 1.0e-10, max_iterations: 20000}");
    Eigen::MatrixXd x = Eigen::MatrixXd::Zero(t.reduced.A.rows(), 3);
    const SolveSummary sum = s->solve(t.reduced.A, t.reduced.b, x);
    REQUIRE(sum.termination == Termination::Converged);
    return sum.iterations;
  };
  const int mg = iterations("petsc_mg"), cg = iterations("conjugate_gradient");
  INFO("petsc_mg " << mg << ", conjugate_gradient " << cg);
  CHECK(4 * mg < cg);
}

TEST_CASE("petsc solvers stop where fairshape's stopping rules say", "[solver][petsc]") {
  const TestSystem& t = bilaplacian_system();
  for (const char* name : kPetscSolvers) {
    INFO(name);
    {  // tolerance 0: a fixed schedule of exactly max_iterations
      auto s = make(name, Backend::Optimized, "{tolerance: 0, max_iterations: 4}");
      Eigen::MatrixXd x = Eigen::MatrixXd::Zero(t.reduced.A.rows(), 3);
      const SolveSummary sum = s->solve(t.reduced.A, t.reduced.b, x);
      CHECK(sum.termination == Termination::ScheduleCompleted);
      CHECK(sum.iterations == 4);
    }
    {  // the cap before the tolerance is not convergence
      auto s = make(name, Backend::Optimized, "{tolerance: 1.0e-14, max_iterations: 3}");
      Eigen::MatrixXd x = Eigen::MatrixXd::Zero(t.reduced.A.rows(), 3);
      CHECK(s->solve(t.reduced.A, t.reduced.b, x).termination == Termination::MaxIterations);
    }
    {  // a callback that says stop
      auto s = make(name, Backend::Optimized, "{tolerance: 1.0e-14, max_iterations: 1000}");
      Eigen::MatrixXd x = Eigen::MatrixXd::Zero(t.reduced.A.rows(), 3);
      const SolveSummary sum = s->solve(t.reduced.A, t.reduced.b, x, [](const IterationRecord& r) { return r.iteration < 2; });
      CHECK_FALSE(sum.termination == Termination::Converged);
      CHECK(x.allFinite());
    }
  }
}

TEST_CASE("petsc solvers refuse what they cannot honour, naming the key", "[solver][petsc]") {
  const auto refused = [](const std::string& name, const std::string& options) {
    try {
      auto s = make(name, Backend::Optimized, options);
      const TestSystem& t = bilaplacian_system();
      Eigen::MatrixXd x = Eigen::MatrixXd::Zero(t.reduced.A.rows(), 3);
      s->solve(t.reduced.A, t.reduced.b, x);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK_THAT(refused("petsc_mg", "{petsc: {options: '-mg_levels_ksp_maxit 3'}}"),
             Catch::Contains("-mg_levels_ksp_maxit") && Catch::Contains("not used"));
  CHECK_THAT(refused("petsc_boomeramg", "{check_every: 5}"), Catch::Contains("check_every"));
  CHECK_THAT(refused("petsc_mg", "{petsc_mg: {smoother: jacobi}}"), Catch::Contains("smoother") && Catch::Contains("sor"));
  CHECK_THAT(refused("petsc_mg", "{petsc: {options: '-ksp_type gmres'}}"), Catch::Contains("-ksp_type"));
  CHECK_THAT(refused("petsc_mg", "{petsc: {launcher: 'mpirun -np 2'}}"), Catch::Contains("{ranks}"));
  CHECK_THAT(refused("petsc_mg", "{petsc: {ranks: 2, launcher: 'mpirun -np {ranks}'}, energy_tolerance: 1.0e-6}"),
             Catch::Contains("energy_tolerance"));
  CHECK_THAT(refused("petsc_boomeramg", "{petsc_boomeramg: {coarsen: nonsense}}"), Catch::Contains("coarsen"));

  // petsc_mg without a hierarchy: a clear refusal, not a one-level solve presented as multigrid
  Config cfg(YAML::Load("{}"), "solver");
  auto s = components().solvers.create("petsc_mg", Backend::Optimized, cfg);
  const TestSystem& t = bilaplacian_system();
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(t.reduced.A.rows(), 3);
  CHECK_THROWS_WITH(s->solve(t.reduced.A, t.reduced.b, x), Catch::Contains("no hierarchy"));
}

TEST_CASE("many petsc solvers in one process do not exhaust PETSc's options database", "[solver][petsc]") {
  // PETSc 3.18 keeps at most 512 options; each solver inserts about 20 under its own prefix.
  const TestSystem& t = bilaplacian_system();
  for (int k = 0; k < 60; ++k) {
    auto s = make("petsc_boomeramg", Backend::Optimized, "{tolerance: 1.0e-6, max_iterations: 2000}");
    Eigen::MatrixXd x = Eigen::MatrixXd::Zero(t.reduced.A.rows(), 1);
    REQUIRE(s->solve(t.reduced.A, t.reduced.b.leftCols(1), x).termination == Termination::Converged);
  }
}
