// Micro-benchmarks of the solver kernels on the thin-plate system of the cow (reduced, 30% of
// the vertices fixed): one Gauss-Seidel sweep, reference (lexicographic) vs optimized
// (multicolour, TBB) over thread counts, and the CHOLMOD vs Eigen LDLT factorization.
//   build/bin/solver_kernels_benchmark --benchmark_format=csv > kernels.csv
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "energy/laplacian.h"
#include "experiment/components.h"
#include "io/mesh_io.h"
#include "problem/constrained_system.h"

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

}  // namespace
}  // namespace fairshape

BENCHMARK_MAIN();
