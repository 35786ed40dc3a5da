// `fairshape run`: validate every run of an experiment, then execute them (in this process,
// in --jobs worker processes, or one --shard of them), appending one CSV row per run.
#pragma once

#include <string>
#include <vector>

namespace fairshape {

struct Slice {
  int index = 0, count = 1;  // runs whose position p satisfies p % count == index
  static Slice parse(const std::string& text, const std::string& option);  // "i/n", 0 <= i < n
};

struct SweepOptions {
  std::string config_path;
  std::vector<std::string> sets;     // --set key=value
  std::vector<std::string> filters;  // --filter key=value: only runs whose swept key has that value
  std::string out_dir;               // empty: results/<name>/<timestamp>_<sha7>
  bool resume = false, force = false;
  int jobs = 1;
  Slice shard;                 // --shard i/n
  Slice worker;                // internal: --worker i/n, set for processes spawned by --jobs
  std::string executable;      // this program, to spawn workers
};

//! Exit status: 0 when every run converged or hit its iteration cap, 3 when some run failed
//! (its row says why), 2 for an invalid config (nothing was run). \throw Error for I/O problems.
int run_sweep(const SweepOptions& opt);

//! `fairshape merge`: rows of several runs.csv joined (columns united, duplicate run_ids kept once).
void merge_run_tables(const std::vector<std::string>& inputs, const std::string& output);

}  // namespace fairshape
