// run.json: what produced a result folder (commit and dirty flag as built, compiler, flags,
// library versions, machine, threads, seed, the resolved config, and one record per session
// that wrote to it), so any number can be traced and reproduced.
#pragma once

#include <nlohmann/json.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "fairshape/core/effective_options.h"

namespace fairshape {

nlohmann::json yaml_to_json(const YAML::Node& n);
nlohmann::json build_and_machine_info();  // version, git, compiler, flags, libraries, CPU, threads
//! "fairshape 0.1.0 (commit <sha>[, modified])": the project version and the commit as built.
std::string version_string();
std::string git_short_sha();             // 7 hex digits, or "nogit"
std::string utc_timestamp(const char* format = "%Y-%m-%dT%H:%M:%SZ");

struct SweepOptions;

//! The options every point used (fairshape/core/effective_options.h), as
//! {"common": {key: value}, "by_run": {run_id: {key: value}}}: a key with one value in every
//! point is listed once under common, the others per run.
nlohmann::json effective_options_json(const std::vector<std::pair<std::string, EffectiveOptions>>& runs);

//! run.json of an output folder: written once with the build, the machine and the resolved
//! config (and config.resolved.yaml beside it); each `fairshape run` on the folder (the first
//! and every --resume) appends a session: argv, --set, --filter, shard, jobs, the SHA-256 of
//! every input file, times and exit status, and the effective options of the points it validated
//! (effective_options_json). A resume never rewrites what came before.
class RunJournal {
 public:
  RunJournal(const std::filesystem::path& dir, const SweepOptions& opt, const YAML::Node& root, const std::string& name,
             const std::vector<std::string>& inputs, std::size_t planned, std::size_t already_done,
             nlohmann::json effective_options);
  void close(int exit_status, std::size_t runs_done);

 private:
  std::filesystem::path path_;
  nlohmann::json journal_;
};

}  // namespace fairshape
