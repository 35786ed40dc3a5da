// `fairshape run`: validate the points of an experiment, then execute them in worker
// processes that a supervisor watches, appending each run's rows to the tables of the
// output folder. Exit status (the same for every run kind):
//   0  every run succeeded (converged, energy_stalled or schedule_completed);
//   2  invalid input, config or command line: nothing was run;
//   3  some run did not succeed (its row's termination and message say why);
//   1  an internal error outside any run; 128+N  interrupted by signal N.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace YAML {
class Node;
}

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
  bool retry_failed = false;         // --retry-failed: a resume runs the failed rows again
  bool dry_run = false;              // --dry-run: print the points and their ids, run nothing
  bool smoke = false;                // --smoke: the config's CI-sized variant (its smoke: block)
  int jobs = 1;
  // --in-process: run the points in this process (a debugger reaches the paper code) instead of
  // in a worker the supervisor watches; a crash then ends the command instead of one run.
  bool in_process = false;
  Slice shard;                 // --shard i/n
  Slice worker;                // internal: --worker i/n, set for processes the supervisor starts
  bool is_worker = false;      // this process is one of them
  std::string executable;      // this program, to spawn workers
  std::vector<std::string> argv;  // the command line, for run.json
};

//! \return the exit status above. \throw InvalidConfig for invalid input (exit 2).
int run_sweep(const SweepOptions& opt);

//! What `fairshape run --dry-run` checks, without printing or writing anything: the config
//! loads and every point the options select (shard, filters) validates.
struct SweepCheck {
  std::string name;             // the experiment's `name`
  std::string kind;             // its run kind
  std::size_t sweep_points = 0; // points of the whole sweep
  std::size_t selected = 0;     // points the options select
};
//! \throw InvalidConfig naming every problem and the points that have it (exit 2).
SweepCheck check_sweep(const SweepOptions& opt);

//! The keys (dotted paths) whose values differ between configs `a` and `b`, each appended to
//! `out` as "key (A IN_A, B IN_B)": by default a stored config ("there") against the current one.
void differing_keys(const YAML::Node& a, const YAML::Node& b, const std::string& path, std::vector<std::string>& out,
                    const std::string& in_a = "there", const std::string& in_b = "now");

//! `fairshape merge OUT IN...`: the shards' output folders joined into OUT (every table, and
//! a run.json naming each shard); or, given CSV files, those tables joined into OUT.csv. A
//! run's rows come from the first input holding that run. Inputs of different experiments (their
//! config.resolved.yaml differ, for tables the one beside each) are refused, naming the keys; CSV
//! tables without a config beside them get a `source` column naming the file of each row.
void merge_results(const std::vector<std::string>& inputs, const std::string& output);

}  // namespace fairshape
