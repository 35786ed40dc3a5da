#include "fairshape/experiment/slurm_array.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <regex>
#include <sstream>

#include "fairshape/core/atomic_file.h"
#include "fairshape/core/error.h"
#include "fairshape/experiment/run_metadata.h"

namespace fairshape {
namespace fs = std::filesystem;
namespace {

// sbatch splits an #SBATCH line at white space and expands %-patterns in file names: a path
// holding either would silently name another file, so it is refused.
void check_sbatch_path(const fs::path& p, const std::string& what) {
  const std::string s = p.string();
  if (s.find_first_of(" \t\n\"'%\\") != std::string::npos)
    throw InvalidConfig(what + " '" + s + "': an #SBATCH line cannot hold a path with spaces, quotes, '\\' or '%'; "
                        "choose a folder without them");
}

void resource_lines(std::ostream& os, const SlurmResources& r, bool with_cpus) {
  if (!r.partition.empty()) os << "#SBATCH --partition=" << r.partition << "\n";
  if (!r.time.empty()) os << "#SBATCH --time=" << r.time << "\n";
  if (with_cpus && r.cpus_per_task > 0) os << "#SBATCH --cpus-per-task=" << r.cpus_per_task << "\n";
  if (!r.mem.empty()) os << "#SBATCH --mem=" << r.mem << "\n";
  for (const auto& e : r.extra) os << "#SBATCH " << e << "\n";
}

// The --setup lines, after the #SBATCH block (sbatch reads no #SBATCH line after a command)
// and before anything else the job runs.
void setup_lines(std::ostream& os, const SlurmArrayJob& job) {
  if (job.setup.empty()) return;
  os << "# Set-up given to `fairshape submit --setup`:\n";
  for (const auto& line : job.setup) os << line << "\n";
}

std::string slurm_dir(const SlurmArrayJob& job) { return (job.out_dir / "slurm").string(); }

// The lines every script starts with: what wrote it and how to submit it by hand.
void header(std::ostream& os, const SlurmArrayJob& job, const std::string& what) {
  os << "#!/bin/bash\n"
     << "# " << what << "\n"
     << "# Written by `fairshape submit --slurm` (" << version_string() << ") for the experiment '"
     << job.name << "': " << job.points << " point(s) in " << job.tasks << " shard(s).\n"
     << "# Submit the array and the merge job that waits for it (what --now does):\n"
     << "#   bash " << shell_quote(slurm_dir(job) + "/submit.sh") << "\n"
     << "# or by hand:\n"
     << "#   array=$(sbatch --parsable " << shell_quote(slurm_dir(job) + "/array.sbatch") << ")\n"
     << "#   sbatch --dependency=afterok:${array%%;*} " << shell_quote(slurm_dir(job) + "/merge.sbatch") << "\n"
     << "# Submitting the array again runs only what is missing: every task resumes its shard.\n";
}

}  // namespace

void check_slurm_time(const std::string& text) {
  static const std::regex forms(R"(\d+|\d+:\d+|\d+:\d+:\d+|\d+-\d+|\d+-\d+:\d+|\d+-\d+:\d+:\d+|INFINITE|UNLIMITED)");
  if (!std::regex_match(text, forms))
    throw InvalidConfig("--time '" + text + "': not a Slurm time limit (valid: M, M:S, H:M:S, D-H, D-H:M, D-H:M:S, "
                        "INFINITE; e.g. 30, 2:00:00, 1-12:00:00)");
}

void check_slurm_memory(const std::string& text) {
  static const std::regex form(R"(\d+[KMGT]?)");
  if (!std::regex_match(text, form))
    throw InvalidConfig("--mem '" + text + "': not a Slurm memory size (valid: an integer in megabytes, or with the "
                        "unit K, M, G or T; e.g. 4000, 16G)");
}

void check_slurm_partition(const std::string& text) {
  static const std::regex form(R"([A-Za-z0-9_.-]+(,[A-Za-z0-9_.-]+)*)");
  if (!std::regex_match(text, form))
    throw InvalidConfig("--partition '" + text + "': not a partition name (valid: letters, digits, '_', '.', '-'; "
                        "several separated by commas)");
}

void check_sbatch_arg(const std::string& text) {
  // The scripts write these themselves, or have an option of their own that is checked.
  static const std::vector<std::pair<std::string, std::string>> owned = {
      {"--array", "--array-size"},        {"--partition", "--partition"},  {"--time", "--time"},
      {"--mem", "--mem"},                 {"--cpus-per-task", "--cpus-per-task"},
      {"--output", "the scripts' logs in OUT/slurm/logs"}, {"--error", "the scripts' logs in OUT/slurm/logs"},
      {"--chdir", "the directory submit runs in"},          {"--job-name", "the experiment's name"},
      {"--dependency", "the merge job's afterok"},          {"--open-mode", "the scripts (append)"},
      {"--requeue", "the array script"},                    {"--kill-on-invalid-dep", "the merge script"},
      {"--parsable", "--now"}};
  static const std::regex form(R"(--[A-Za-z][A-Za-z0-9-]*(=[^\s'"\\]+)?)");
  if (!std::regex_match(text, form))
    throw InvalidConfig("--sbatch-arg '" + text + "': not an sbatch option (valid: --name or --name=value, one word "
                        "without spaces or quotes, e.g. --sbatch-arg=--account=proj, --sbatch-arg=--gres=gpu:1; an "
                        "#SBATCH line ends at white space)");
  const std::string name = text.substr(0, text.find('='));
  for (const auto& [option, by] : owned)
    if (name == option)
      throw InvalidConfig("--sbatch-arg '" + text + "': " + option + " is set by " + by + " (valid: any other sbatch "
                          "option, e.g. --account, --qos, --constraint, --gres)");
}

void check_setup_line(const std::string& text) {
  if (text.find_first_not_of(" \t") == std::string::npos)
    throw InvalidConfig("--setup '" + text + "': an empty line (valid: one shell command, e.g. 'module load gcc')");
  for (char c : text)
    if (c == '\n' || c == '\r' || c == '\0')
      throw InvalidConfig("--setup: one line per --setup (valid: a shell command without line breaks; give "
                          "--setup again for the next line)");
}

std::string shell_quote(const std::string& word) {
  std::string out(1, '\'');
  for (char c : word) {
    if (c == '\'') out.append("'\\''");
    else out.push_back(c);
  }
  out.push_back('\'');
  return out;
}

std::string array_script(const SlurmArrayJob& job) {
  std::ostringstream os;
  header(os, job, "The job array: task i (0 .. N-1, numbered like --shard i/n) runs shard i/N of the sweep.");
  const std::string n = std::to_string(job.tasks);
  const std::string shards = (job.out_dir / "shards").string();
  os << "#SBATCH --job-name=fairshape-" << job.name << "\n"
     << "#SBATCH --array=0-" << job.tasks - 1 << "\n"
     // A requeued or preempted task starts again and --resume continues its shard: finished
     // runs are skipped, a run cut off is rolled back and runs again.
     << "#SBATCH --requeue\n"
     << "#SBATCH --open-mode=append\n"
     << "#SBATCH --output=" << slurm_dir(job) << "/logs/shard-%a.log\n"
     << "#SBATCH --chdir=" << job.work_dir.string() << "\n";
  resource_lines(os, job.resources, true);
  setup_lines(os, job);
  os << "shard=\"${SLURM_ARRAY_TASK_ID:?this is a job array script: submit it with sbatch, see above}\"\n"
     << "echo \"fairshape: shard $shard/" << n << ", attempt $(( ${SLURM_RESTART_COUNT:-0} + 1 )), "
     << "$(date -u +%Y-%m-%dT%H:%M:%SZ) on $(hostname)\"\n"
     << "status=0\n"
     << shell_quote(job.executable) << " run " << shell_quote(job.config_path) << " --shard \"$shard/" << n
     << "\" --resume --out " << shell_quote(shards + "/") << "\"$shard\"";
  for (const auto& o : job.run_options) os << " " << shell_quote(o);
  os << " || status=$?\n"
     << "# 3: the shard ran and some run did not succeed (its row says why); the shard is complete,\n"
     << "# so the merge may go on. 2 (invalid input) and signals fail the task, and the merge is then cancelled.\n"
     << "if [ \"$status\" -eq 3 ]; then\n"
     << "  echo \"fairshape: shard $shard/" << n << ": some runs did not succeed (see their rows)\"\n"
     << "  exit 0\n"
     << "fi\n"
     << "exit \"$status\"\n";
  return os.str();
}

std::string merge_script(const SlurmArrayJob& job) {
  std::ostringstream os;
  header(os, job, "The merge job: joins the shards' folders into the output folder once every task succeeded.");
  os << "#SBATCH --job-name=fairshape-" << job.name << "-merge\n"
     << "#SBATCH --open-mode=append\n"
     << "#SBATCH --output=" << slurm_dir(job) << "/logs/merge.log\n"
     << "#SBATCH --chdir=" << job.work_dir.string() << "\n"
     // A failed task never satisfies afterok: the merge is then cancelled, not left pending.
     << "#SBATCH --kill-on-invalid-dep=yes\n";
  resource_lines(os, job.resources, false);
  setup_lines(os, job);  // before `set -u`: module scripts read variables that may be unset
  os << "set -euo pipefail\n"
     << "shards=()\n"
     << "for ((i = 0; i < " << job.tasks << "; ++i)); do shards+=(" << shell_quote((job.out_dir / "shards").string() + "/")
     << "\"$i\"); done\n"
     << "exec " << shell_quote(job.executable) << " merge " << shell_quote(job.out_dir.string()) << " \"${shards[@]}\"\n";
  return os.str();
}

std::string submit_script(const SlurmArrayJob& job) {
  std::ostringstream os;
  header(os, job, "Submits the array, then the merge job with --dependency=afterok on it.");
  os << "set -euo pipefail\n"
     << "array=$(sbatch --parsable " << shell_quote(slurm_dir(job) + "/array.sbatch") << ")\n"
     << "array=${array%%;*}\n"
     << "merge=$(sbatch --parsable --dependency=afterok:\"$array\" " << shell_quote(slurm_dir(job) + "/merge.sbatch")
     << ")\n"
     << "echo \"array job: $array\"\n"
     << "echo \"merge job: ${merge%%;*}\"\n";
  return os.str();
}

SlurmScripts write_slurm_scripts(const SlurmArrayJob& job) {
  check_sbatch_path(job.out_dir, "--out");
  check_sbatch_path(job.work_dir, "the working directory");
  const fs::path dir = job.out_dir / "slurm";
  fs::create_directories(dir / "logs");
  const SlurmScripts s{dir / "array.sbatch", dir / "merge.sbatch", dir / "submit.sh"};
  write_atomically(s.array, [&](std::ostream& os) { os << array_script(job); });
  write_atomically(s.merge, [&](std::ostream& os) { os << merge_script(job); });
  write_atomically(s.submit, [&](std::ostream& os) { os << submit_script(job); });
  for (const auto& p : {s.array, s.merge, s.submit})
    fs::permissions(p, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec, fs::perm_options::add);
  return s;
}

std::string find_sbatch() {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string d; std::getline(dirs, d, ':');) {
    if (d.empty()) continue;
    const fs::path candidate = fs::path(d) / "sbatch";
    if (::access(candidate.c_str(), X_OK) == 0 && fs::is_regular_file(candidate)) return candidate.string();
  }
  return "";
}

std::string sbatch_submit(const std::string& sbatch, const fs::path& script, const std::string& dependency) {
  std::string cmd = shell_quote(sbatch) + " --parsable";
  if (!dependency.empty()) cmd.append(" ").append(shell_quote(std::string("--dependency=").append(dependency)));
  cmd.append(" ").append(shell_quote(script.string())).append(" 2>&1");
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) throw Error("cannot start " + sbatch);
  std::string out;
  char buf[512];
  while (std::fgets(buf, sizeof buf, pipe)) out += buf;
  const int status = ::pclose(pipe);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  // --parsable prints "jobid" or "jobid;cluster" as its last line (warnings may come first).
  const std::string last = out.substr(out.find_last_of('\n') == std::string::npos ? 0 : out.find_last_of('\n') + 1);
  const std::string id = last.substr(0, last.find(';'));
  if (status != 0 || id.empty() || id.find_first_not_of("0123456789") != std::string::npos) {
    std::string msg = "sbatch " + script.string() + " failed";
    if (status != 0) msg.append(" (status ").append(std::to_string(status)).append(")");
    msg.append(": ").append(out.empty() ? std::string("no output") : out);
    throw Error(msg);
  }
  return id;
}

}  // namespace fairshape
