// Benchmarks of the solver kernels, each beside the peer it is judged against:
//   - Gauss-Seidel sweeps on the thin-plate system of the base cow (in cache), reference
//     (lexicographic) vs optimized (multicolour, TBB), and CHOLMOD vs Eigen LDLT factoring;
//   - STREAM triad (a = b + s·c) and one sweep of the level-3/4 cow edit (out of cache), point
//     multicolour and block multicolour on the renumbered system, as bytes/s: share of triad;
//   - the stretch+bend H of a cow level assembled by the reference and optimized back ends;
//   - the level-2 edit converged from scratch (analysis included) by CHOLMOD and by
//     multigrid-preconditioned CG (V-cycles alone: configs/boier-martin/solvers.yaml).
// Arguments: /threads, or /level/threads.
//   build/bin/solver_kernels_benchmark --benchmark_format=csv > kernels.csv
#include <benchmark/benchmark.h>

#include <map>
#include <tbb/global_control.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "cow_edit_problem.h"
#include "fairshape/energy/laplacian.h"
#include "fairshape/energy/local_quadratic.h"
#include "fairshape/solver/block_ordering.h"
#include "fairshape/solver/multigrid.h"
#include "fairshape/solver/parallel_kernels.h"
#include "fairshape/experiment/components.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/problem/constrained_system.h"
#include "fairshape/problem/least_squares.h"
#include "fairshape/solver/independent_columns.h"
#include "fairshape/solver/level_operators.h"
#include "fairshape/core/timer.h"
#include <Eigen/SparseCholesky>
#include "fairshape/problem/least_squares.h"

namespace fairshape {
namespace {

const ReducedSystem& cow_system() {
  static const ReducedSystem r = [] {
    const SurfaceMesh m = read_mesh(std::string(FAIRSHAPE_SOURCE_DIR) + "/data/cow.off");
    const SparseMatrix U = umbrella_operator(m);
    ConstrainedSystem s{SparseMatrix(U.transpose()) * U, Eigen::MatrixXd::Zero(m.n_vertices(), 3), {}, {}};
    const double lo = m.positions().col(0).minCoeff(), hi = m.positions().col(0).maxCoeff();
    for (int v = 0; v < m.n_vertices(); ++v)
      if (m.positions()(v, 0) < lo + 0.3 * (hi - lo)) s.fixed.push_back(v);
    s.fixed_values = Eigen::MatrixXd::Random(static_cast<Eigen::Index>(s.fixed.size()), 3);
    return reduce(s);
  }();
  return r;
}

void run_sweeps(benchmark::State& state, Backend backend) {
  const auto& r = cow_system();
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  Config cfg(YAML::Load("{tolerance: 0.0, max_iterations: 10, check_every: 10}"), "solver");
  auto gs = components().solvers.create("gauss_seidel", backend, cfg);
  gs->analyze(r.A);
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(r.A.rows(), 3);
  for (auto _ : state) {
    gs->solve(r.A, r.b, x);
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["rows"] = static_cast<double>(r.A.rows());
  state.counters["sweeps/s"] = benchmark::Counter(10.0 * state.iterations(), benchmark::Counter::kIsRate);
}

void BM_GaussSeidel10Sweeps_Reference(benchmark::State& s) { run_sweeps(s, Backend::Reference); }
void BM_GaussSeidel10Sweeps_Optimized(benchmark::State& s) { run_sweeps(s, Backend::Optimized); }
BENCHMARK(BM_GaussSeidel10Sweeps_Reference)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_GaussSeidel10Sweeps_Optimized)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

void run_factor(benchmark::State& state, Backend backend) {
  const auto& r = cow_system();
  Config none;
  for (auto _ : state) {
    auto chol = components().solvers.create("cholesky", backend, none);
    chol->analyze(r.A);
    benchmark::ClobberMemory();
  }
}
void BM_CholeskyAnalyzeFactor_EigenLDLT(benchmark::State& s) { run_factor(s, Backend::Reference); }
void BM_CholeskyAnalyzeFactor_CHOLMOD(benchmark::State& s) { run_factor(s, Backend::Optimized); }
BENCHMARK(BM_CholeskyAnalyzeFactor_EigenLDLT)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CholeskyAnalyzeFactor_CHOLMOD)->Unit(benchmark::kMillisecond);

// STREAM triad over three 8M-double arrays (192 MB: far beyond any cache); 24 bytes move
// per element, STREAM's own count.
void BM_StreamTriad(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  const std::size_t n = 8u << 20;
  std::vector<double> a(n), b(n, 1.0), c(n, 2.0);
  for (auto _ : state) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1 << 16), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i < r.end(); ++i) a[i] = b[i] + 3.0 * c[i];
    });
    benchmark::DoNotOptimize(a.data());
  }
  state.counters["bytes_per_second"] = benchmark::Counter(24.0 * n * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_StreamTriad)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// The reduced level-L cow edit (the multigrid's finest system) and one forward sweep of it by a
// smoother, timed. Bytes: the least a sweep must move — A's values and column indices once
// (12 bytes per entry, 4 per row pointer), x read and written and b read once (3 doubles each
// per row).
RowSparseMatrix cow_edit_system(int level) {
  const EditProblem& p = bench::cow_edit(level, level).ladder.problems.back();
  const std::vector<int> fixed = reached_columns(p.constraints.A);
  return RowSparseMatrix(reduce({p.H, p.g, fixed, Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(fixed.size()), 3)}).A);
}

template <class Smoother>
void time_sweeps(benchmark::State& state, const RowSparseMatrix& A, const Smoother& smoother) {
  RowBlock x = RowBlock::Zero(A.rows(), 3), b = RowBlock::Ones(A.rows(), 3);
  for (auto _ : state) {
    smoother.sweep(A, x, b, 1.0, true);
    benchmark::DoNotOptimize(x.data());
  }
  const double bytes = 12.0 * static_cast<double>(A.nonZeros()) + (4.0 + 3 * 24.0) * static_cast<double>(A.rows());
  state.counters["rows"] = static_cast<double>(A.rows());
  state.counters["colors"] = smoother.colors();
  state.counters["bytes_per_second"] = benchmark::Counter(bytes * state.iterations(), benchmark::Counter::kIsRate);
}

// Point multicolour over the subdivision numbering.
void BM_MulticolorSweep_CowEdit(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(1)));
  const RowSparseMatrix A = cow_edit_system(static_cast<int>(state.range(0)));
  MulticolorSmoother smoother;
  smoother.analyze(A);
  time_sweeps(state, A, smoother);
}
BENCHMARK(BM_MulticolorSweep_CowEdit)->Args({3, 1})->Args({3, 2})->Args({4, 2})->Unit(benchmark::kMillisecond)->UseRealTime();

// Block multicolour on the renumbered system (what multigrid's optimized back end runs by default).
void BM_BlockSweep_CowEdit(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(1)));
  const RowSparseMatrix system = cow_edit_system(static_cast<int>(state.range(0)));
  const BlockOrdering ordering = BlockOrdering::build(system, BlockOrdering::block_size_for(system.rows(), MultigridOptions().block_size));
  const RowSparseMatrix A = ordering.permute(system);
  BlockSmoother smoother;
  smoother.analyze(A, ordering.color_blocks);
  time_sweeps(state, A, smoother);
}
BENCHMARK(BM_BlockSweep_CowEdit)->Args({3, 1})->Args({3, 2})->Args({4, 2})->Unit(benchmark::kMillisecond)->UseRealTime();

void run_assembly(benchmark::State& state, Backend backend) {
  const int level = static_cast<int>(state.range(0));
  const SurfaceMesh& m = bench::cow_edit(level, level).hierarchy->mesh(level);
  for (auto _ : state) benchmark::DoNotOptimize(stretch_bend_hessian(m, {0.1, 1.0}, backend).nonZeros());
  state.counters["vertices"] = m.n_vertices();
}
void BM_StretchBendAssembly_Reference(benchmark::State& s) { run_assembly(s, Backend::Reference); }
void BM_StretchBendAssembly_Optimized(benchmark::State& s) { run_assembly(s, Backend::Optimized); }
BENCHMARK(BM_StretchBendAssembly_Reference)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_StretchBendAssembly_Optimized)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime();

// From scratch, as a user meets it: the solver's analysis (factorization, hierarchy set-up)
// and the solve, to a 1e-10 relative residual for the iterative ones.
void run_converged(benchmark::State& state, const std::string& solver) {
  const int level = static_cast<int>(state.range(0));
  const bench::CowEdit& e = bench::cow_edit(level, level, solver);
  const EditProblem& p = e.ladder.problems.back();
  int iterations = 0;
  for (auto _ : state) {
    Config cfg(YAML::Load("{tolerance: 1.0e-10, max_iterations: 1000}"), "solver");
    auto s = components().solvers.create(solver, Backend::Optimized, cfg);
    const EditSolution sol = solve_edit(p, ConstraintMode::Paper, *s, Backend::Optimized);
    iterations = sol.summary.iterations;
    benchmark::DoNotOptimize(sol.delta.data());
  }
  state.counters["iterations"] = iterations;
  state.counters["unknowns"] = static_cast<double>(p.H.rows());
}
void BM_ConvergedEdit_CHOLMOD(benchmark::State& s) { run_converged(s, "cholesky"); }
void BM_ConvergedEdit_MultigridCG(benchmark::State& s) { run_converged(s, "multigrid_cg"); }
BENCHMARK(BM_ConvergedEdit_CHOLMOD)->Arg(2)->Iterations(1)->Repetitions(3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ConvergedEdit_MultigridCG)->Arg(2)->Iterations(1)->Repetitions(3)->Unit(benchmark::kMillisecond)->UseRealTime();

// The paper split's reduced system of the level-L edit (constrained vertices at their
// minimum-norm values, as solve_edit's paper mode sets them), solved by multigrid-preconditioned
// CG to 1e-10 with the block of three columns, or with its independent columns only (a single
// handle's right-hand side has rank 1). The analysis is outside the timing; both
// variants run in one process on the same system, so their ratio is a same-run ratio.
struct SplitSystem {
  ReducedSystem reduced;
  std::shared_ptr<const LevelOperators> levels;
};

const SplitSystem& split_system(int level) {
  static std::map<int, SplitSystem> cache;
  if (auto it = cache.find(level); it != cache.end()) return it->second;
  const EditProblem& p = bench::cow_edit(level, level, "multigrid_cg").ladder.problems.back();
  const std::vector<int> fixed = reached_columns(p.constraints.A);
  const MinNormLeastSquares ls(p.constraints.A * row_picker(p.constraints.A.cols(), fixed), Backend::Optimized);
  return cache[level] = {reduce({p.H, p.g, fixed, ls.solve(p.constraints.C).X}), p.levels};
}

void run_right_hand_sides(benchmark::State& state, bool independent) {
  const SplitSystem& s = split_system(static_cast<int>(state.range(0)));
  Config cfg(YAML::Load("{tolerance: 1.0e-10, max_iterations: 1000}"), "solver");
  auto solver = components().solvers.create("multigrid_cg", Backend::Optimized, cfg);
  solver->set_levels(s.levels, {s.reduced.free, 1});
  solver->analyze(s.reduced.A);
  SolveSummary summary;
  for (auto _ : state) {
    Eigen::MatrixXd x = Eigen::MatrixXd::Zero(s.reduced.A.rows(), s.reduced.b.cols());
    summary = independent ? solve_independent_columns(*solver, s.reduced.A, s.reduced.b, x)
                          : solver->solve(s.reduced.A, s.reduced.b, x);
    benchmark::DoNotOptimize(x.data());
  }
  const auto d = dependent_columns(s.reduced.b);
  state.counters["columns_solved"] = independent && d ? static_cast<double>(d->independent.size()) : 3.0;
  state.counters["iterations"] = summary.iterations;
  state.counters["residual"] = summary.residual;
  state.counters["unknowns"] = static_cast<double>(s.reduced.A.rows());
}
void BM_SplitSolve_BlockOfThree(benchmark::State& s) { run_right_hand_sides(s, false); }
void BM_SplitSolve_IndependentColumns(benchmark::State& s) { run_right_hand_sides(s, true); }
BENCHMARK(BM_SplitSolve_BlockOfThree)->Arg(3)->Iterations(1)->Repetitions(3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SplitSolve_IndependentColumns)->Arg(3)->Iterations(1)->Repetitions(3)->Unit(benchmark::kMillisecond)->UseRealTime();

// Issue 27's peers in one run: the level-L split system's x column (the handle's right-hand side
// has rank 1) solved from scratch — set-up (factorization, hierarchy, PETSc's PCMG/GAMG/hypre
// set-up) and solve — to a 1e-10 relative residual, each solver by its registered name, one
// thread for the peers as PETSc runs here. Counters: setup_s, solve_s, iterations, and the
// relative error against CHOLMOD's solution of the same column.
const Eigen::VectorXd& direct_column(int level) {
  static std::map<int, Eigen::VectorXd> cache;
  if (auto it = cache.find(level); it != cache.end()) return it->second;
  const SplitSystem& s = split_system(level);
  Config none;
  auto chol = components().solvers.create("cholesky", Backend::Optimized, none);
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(s.reduced.A.rows(), 1);
  chol->solve(s.reduced.A, s.reduced.b.leftCols(1), x);
  return cache[level] = x.col(0);
}

void run_peer(benchmark::State& state, const std::string& solver) {
  const int level = static_cast<int>(state.range(0));
  const SplitSystem& s = split_system(level);
  const Eigen::VectorXd& exact = direct_column(level);
  const Eigen::MatrixXd b = s.reduced.b.leftCols(1);
  double setup_s = 0, solve_s = 0;
  SolveSummary summary;
  Eigen::MatrixXd x;
  for (auto _ : state) {
    Config cfg(YAML::Load("{tolerance: 1.0e-10, max_iterations: 5000}"), "solver");
    auto sol = components().solvers.create(solver, Backend::Optimized, cfg);
    const Timer setup;
    if (sol->uses_levels()) sol->set_levels(s.levels, {s.reduced.free, 1});
    sol->analyze(s.reduced.A);
    setup_s = setup.seconds();
    x = Eigen::MatrixXd::Zero(s.reduced.A.rows(), 1);
    const Timer solve;
    summary = sol->solve(s.reduced.A, b, x);
    solve_s = solve.seconds();
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["setup_s"] = setup_s;
  state.counters["solve_s"] = solve_s;
  state.counters["iterations"] = summary.iterations;
  state.counters["converged"] = summary.termination == Termination::Converged ? 1 : 0;
  state.counters["error_vs_cholmod"] = (x.col(0) - exact).norm() / exact.norm();
  state.counters["unknowns"] = static_cast<double>(s.reduced.A.rows());
}
void BM_Peer_CHOLMOD(benchmark::State& s) { run_peer(s, "cholesky"); }
void BM_Peer_MultigridCG(benchmark::State& s) { run_peer(s, "multigrid_cg"); }
BENCHMARK(BM_Peer_CHOLMOD)->Arg(2)->Arg(3)->Iterations(1)->Repetitions(3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Peer_MultigridCG)->Arg(2)->Arg(3)->Iterations(1)->Repetitions(3)->Unit(benchmark::kMillisecond)->UseRealTime();
#if FAIRSHAPE_WITH_PETSC
void BM_Peer_PetscMG(benchmark::State& s) { run_peer(s, "petsc_mg"); }
void BM_Peer_PetscGAMG(benchmark::State& s) { run_peer(s, "petsc_gamg"); }
void BM_Peer_BoomerAMG(benchmark::State& s) { run_peer(s, "petsc_boomeramg"); }
BENCHMARK(BM_Peer_PetscMG)->Arg(2)->Arg(3)->Iterations(1)->Repetitions(3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Peer_PetscGAMG)->Arg(2)->Arg(3)->Iterations(1)->Repetitions(3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Peer_BoomerAMG)->Arg(2)->Arg(3)->Iterations(1)->Repetitions(3)->Unit(benchmark::kMillisecond)->UseRealTime();
#endif

}  // namespace
}  // namespace fairshape

BENCHMARK_MAIN();
