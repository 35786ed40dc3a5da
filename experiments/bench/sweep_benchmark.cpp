// How long a sweep takes to validate before its first run (README, "Limits"): the whole of a
// 10^6-point sweep (1000 seeds × 1000 iteration counts on the cow) and one shard of it, and
// the run ids alone. Sizes in the benchmark names; one iteration each (minutes for the whole).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "fairshape/experiment/config_loader.h"
#include "fairshape/experiment/sweep.h"
#include "fairshape/experiment/sweep_runner.h"

namespace {

std::string million_point_config() {
  const std::string path = (std::filesystem::temp_directory_path() / "fairshape_sweep_benchmark.yaml").string();
  std::ofstream out(path);
  out << "defaults: [" << FAIRSHAPE_SOURCE_DIR << "/configs/smoke/cow_nose_pull.yaml]\nname: million\n"
      << "solver: {type: conjugate_gradient}\nsweep:\n  seed: [";
  for (int i = 0; i < 1000; ++i) out << (i ? ", " : "") << i;
  out << "]\n  solver.max_iterations: [";
  for (int i = 0; i < 1000; ++i) out << (i ? ", " : "") << 100 + i;
  out << "]\n";
  return path;
}

void validate(benchmark::State& state) {
  fairshape::SweepOptions opt;
  opt.config_path = million_point_config();
  opt.shard = {0, static_cast<int>(state.range(0))};
  for (auto _ : state) benchmark::DoNotOptimize(fairshape::check_sweep(opt));
  state.counters["points"] = 1e6 / static_cast<double>(state.range(0));
}
BENCHMARK(validate)->ArgName("shards")->Arg(1000)->Arg(1)->Iterations(1)->Unit(benchmark::kSecond);

void run_ids(benchmark::State& state) {
  const fairshape::SweepSpace space(fairshape::load_experiment_config(million_point_config(), {}));
  for (auto _ : state)
    for (std::size_t i = 0; i < space.size(); ++i) benchmark::DoNotOptimize(space.run_id(i));
  state.counters["points"] = static_cast<double>(space.size());
}
BENCHMARK(run_ids)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
