// A sweep as a Slurm job array (`fairshape submit --slurm`): task i runs
// `fairshape run CONFIG --shard i/N --resume --out DIR/shards/i`, and a merge job, submitted
// with --dependency=afterok on the array, joins the shards into DIR. The scripts live in
// DIR/slurm/ and nothing is written anywhere else.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace fairshape {

//! sbatch's resource options; empty (or 0) leaves the cluster's default. `extra`: any other
//! sbatch options (--account=, --qos=, --constraint=, --gres=), one #SBATCH line each, on every job.
struct SlurmResources {
  std::string partition, time, mem;
  int cpus_per_task = 0;
  std::vector<std::string> extra;
};

//! Slurm's own spellings are checked here, so a typo is refused before anything is written
//! rather than by sbatch afterwards. \throw InvalidConfig naming the option and the forms.
void check_slurm_time(const std::string& text);       // --time: M, M:S, H:M:S, D-H, D-H:M, D-H:M:S
void check_slurm_memory(const std::string& text);     // --mem: an integer with an optional K/M/G/T
void check_slurm_partition(const std::string& text);  // --partition: names separated by commas
void check_sbatch_arg(const std::string& text);        // --sbatch-arg: --name or --name=value, one word
void check_setup_line(const std::string& text);        // --setup: one shell line

struct SlurmArrayJob {
  std::string executable;                // absolute path of fairshape
  std::string config_path;               // absolute
  std::vector<std::string> run_options;  // passed to every task's `fairshape run` (--set k=v, --smoke)
  std::filesystem::path out_dir;         // absolute; shards in out_dir/shards/<i>
  std::filesystem::path work_dir;        // the jobs' working directory: where submit ran
  std::string name;                      // the experiment's name
  int tasks = 1;                         // N, the array's size and the shard count
  std::size_t points = 0;                // for the scripts' header
  SlurmResources resources;
  std::vector<std::string> setup;        // shell lines each job runs before its command (module load ...)
};

struct SlurmScripts {
  std::filesystem::path array, merge, submit;
};

//! The job-array script: task $SLURM_ARRAY_TASK_ID (0..N-1, like --shard i/n) runs its shard.
std::string array_script(const SlurmArrayJob& job);
//! The merge job: `fairshape merge DIR DIR/shards/0 ... DIR/shards/N-1`.
std::string merge_script(const SlurmArrayJob& job);
//! Submits both by hand, with the dependency (what --now does).
std::string submit_script(const SlurmArrayJob& job);
//! Writes the three into DIR/slurm/ (and creates DIR/slurm/logs/).
SlurmScripts write_slurm_scripts(const SlurmArrayJob& job);

//! The absolute path of sbatch found in PATH, or empty.
std::string find_sbatch();
//! `sbatch --parsable [--dependency=D] SCRIPT`: the job id. \throw Error carrying sbatch's output.
std::string sbatch_submit(const std::string& sbatch, const std::filesystem::path& script,
                          const std::string& dependency = "");

//! A word for a POSIX shell: single-quoted, every ' written as '\''.
std::string shell_quote(const std::string& word);

}  // namespace fairshape
