#include "submit_command.h"

#include <filesystem>
#include <fstream>
#include <iostream>

#include "fairshape/core/atomic_file.h"
#include "fairshape/core/error.h"
#include "fairshape/experiment/output_folder.h"
#include "fairshape/experiment/sweep_runner.h"

namespace fairshape::cli {
namespace fs = std::filesystem;
namespace {

// --array-size is parsed here, not by CLI11, so every bad value gets the valid range.
int array_size_of(const std::string& text, std::size_t points) {
  const std::string range = "valid: 1 to " + std::to_string(points) + ", the sweep's point count";
  if (text.empty()) return static_cast<int>(std::min<std::size_t>(points, kDefaultArraySize));
  long long n = 0;
  std::size_t used = 0;
  try {
    n = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size()) throw InvalidConfig("--array-size '" + text + "': not an integer (" + range + ")");
  if (n < 1) throw InvalidConfig("--array-size " + text + ": an array needs at least 1 task (" + range + ")");
  if (static_cast<unsigned long long>(n) > points)
    throw InvalidConfig("--array-size " + text + ": more tasks than the sweep has points, so some shards would be "
                        "empty (" + range + ")");
  return static_cast<int>(n);
}

// A submission starts a folder of its own: one already holding files is refused, never mixed into.
void require_empty(const fs::path& dir) {
  if (!fs::exists(dir)) return;
  if (!fs::is_directory(dir)) throw InvalidConfig("--out " + dir.string() + ": exists and is not a folder");
  for (const auto& e : fs::directory_iterator(dir))
    throw InvalidConfig("--out " + dir.string() + ": holds files already (" + e.path().filename().string() +
                        "); give a new folder (to run a written submission again: sbatch " +
                        (dir / "slurm" / "array.sbatch").string() + ", its tasks resume)");
}

}  // namespace

int cmd_submit(const SubmitArgs& a) {
  if (!a.slurm)
    throw InvalidConfig("submit: name the scheduler (valid: --slurm; for PBS, LSF or SGE arrays run the shards "
                        "yourself, see configs/README.md, \"Other schedulers\")");
  const SlurmResources& r = a.resources;
  if (!r.time.empty()) check_slurm_time(r.time);
  if (!r.mem.empty()) check_slurm_memory(r.mem);
  if (!r.partition.empty()) check_slurm_partition(r.partition);
  for (const auto& e : r.extra) check_sbatch_arg(e);
  for (const auto& line : a.setup) check_setup_line(line);
  std::string sbatch;
  if (a.now && (sbatch = find_sbatch()).empty())
    throw InvalidConfig("--now: sbatch is not on PATH (is this a Slurm login node?); without --now the scripts are "
                        "written and say how to submit them");

  // Every point is validated here, as a serial run would: a bad point is refused before
  // anything is queued, not by one task hours later.
  SweepOptions run;
  run.config_path = a.config;
  run.sets = a.sets;
  run.smoke = a.smoke;
  const SweepCheck sweep = check_sweep(run);
  const int tasks = array_size_of(a.array_size, sweep.selected);
  if (!a.out.empty()) require_empty(a.out);

  SlurmArrayJob job;
  job.executable = fs::read_symlink("/proc/self/exe").string();
  job.config_path = fs::absolute(a.config).lexically_normal().string();
  for (const auto& s : a.sets) job.run_options.insert(job.run_options.end(), {"--set", s});
  if (a.smoke) job.run_options.emplace_back("--smoke");
  job.work_dir = fs::current_path();
  job.name = sweep.name;
  job.tasks = tasks;
  job.points = sweep.selected;
  job.resources = r;
  job.setup = a.setup;
  job.out_dir = fs::absolute(a.out.empty() ? default_out_dir(sweep.name) : fs::path(a.out)).lexically_normal();
  const SlurmScripts scripts = write_slurm_scripts(job);

  std::cout << sweep.name << ": " << sweep.selected << " " << sweep.kind << " point(s) in " << tasks
            << " array task(s) -> " << job.out_dir.string() << "\n"
            << "  " << scripts.array.string() << "\n  " << scripts.merge.string() << "\n";
  if (!a.now) {
    std::cout << "submit with: bash " << scripts.submit.string() << "\n";
    return 0;
  }
  std::string array_id;
  try {
    array_id = sbatch_submit(sbatch, scripts.array);
  } catch (const Error& e) {
    throw Error(std::string(e.what()) + "\nnothing was queued; the scripts stay in " + (job.out_dir / "slurm").string() +
                " (submit them with bash " + scripts.submit.string() + ")");
  }
  std::string merge_id;
  try {
    merge_id = sbatch_submit(sbatch, scripts.merge, "afterok:" + array_id);
  } catch (const Error& e) {
    throw Error(std::string(e.what()) + "\nthe array job " + array_id + " is queued; submit its merge with: sbatch " +
                "--dependency=afterok:" + array_id + " " + scripts.merge.string());
  }
  write_atomically(job.out_dir / "slurm" / "jobs.txt", [&](std::ostream& os) {
    os << "array " << array_id << "\nmerge " << merge_id << "\n";
  });
  std::cout << "array job: " << array_id << "\nmerge job: " << merge_id << "\n";
  return 0;
}

}  // namespace fairshape::cli
