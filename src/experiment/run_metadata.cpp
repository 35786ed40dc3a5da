#include "fairshape/experiment/run_metadata.h"

#include <cholmod.h>
#include <tbb/info.h>
#include <tbb/version.h>

#include <array>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <map>
#include <set>
#include <filesystem>
#include <thread>

#include "fairshape/core/atomic_file.h"
#include "fairshape/core/config.h"
#include "fairshape/experiment/sha256.h"
#include "fairshape/experiment/sweep_runner.h"
#include "fairshape_build_info.h"
#include "fairshape/io/json_io.h"

namespace fairshape {
namespace {

std::string cpu_model() {
  std::ifstream f("/proc/cpuinfo");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

}  // namespace

nlohmann::json yaml_to_json(const YAML::Node& n) {
  if (!n.IsDefined() || n.IsNull()) return nullptr;
  if (n.IsSequence()) {
    auto a = nlohmann::json::array();
    for (const auto& v : n) a.push_back(yaml_to_json(v));
    return a;
  }
  if (n.IsMap()) {
    auto o = nlohmann::json::object();
    for (const auto& kv : n) o[kv.first.as<std::string>()] = yaml_to_json(kv.second);
    return o;
  }
  const std::string& s = n.Scalar();
  if (n.Tag() != "!") {  // unquoted scalars may be numbers or booleans
    long long i;
    double d;
    bool b;
    if (YAML::convert<long long>::decode(n, i)) return i;
    if (YAML::convert<double>::decode(n, d)) return d;
    if (YAML::convert<bool>::decode(n, b)) return b;
  }
  return s;
}

std::string git_short_sha() {
  const std::string sha = FAIRSHAPE_GIT_COMMIT;
  return sha == "unknown" ? "nogit" : sha.substr(0, 7);
}

std::string utc_timestamp(const char* format) {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[64];
  std::strftime(buf, sizeof buf, format, &tm);
  return buf;
}

std::string version_string() {
  return std::string("fairshape ") + FAIRSHAPE_VERSION + " (commit " + FAIRSHAPE_GIT_COMMIT + (FAIRSHAPE_GIT_DIRTY ? ", modified" : "") + ")";
}

nlohmann::json build_and_machine_info() {
  nlohmann::json j;
  j["fairshape_version"] = FAIRSHAPE_VERSION;
  j["git_commit"] = FAIRSHAPE_GIT_COMMIT;  // as built, not as checked out now
  j["git_dirty"] = FAIRSHAPE_GIT_DIRTY;
  j["compiler"] = std::string(FAIRSHAPE_COMPILER_ID) + " " + __VERSION__;
  j["build_type"] = FAIRSHAPE_BUILD_TYPE;
  j["compiler_flags"] = FAIRSHAPE_CXX_FLAGS;
  j["libraries"] = {{"eigen", FAIRSHAPE_EIGEN_VERSION},
                    {"tbb", TBB_VERSION_STRING},
                    {"suitesparse_cholmod", std::to_string(CHOLMOD_MAIN_VERSION) + "." +
                                                std::to_string(CHOLMOD_SUB_VERSION) + "." +
                                                std::to_string(CHOLMOD_SUBSUB_VERSION)},
                    {"ceres", FAIRSHAPE_CERES_VERSION},
                    {"vtk", FAIRSHAPE_VTK_VERSION},
                    {"yaml_cpp", FAIRSHAPE_YAML_CPP_VERSION}};
  j["cpu_model"] = cpu_model();
  j["hardware_threads"] = std::thread::hardware_concurrency();
  j["tbb_default_concurrency"] = tbb::info::default_concurrency();
  return j;
}

namespace {
namespace fs = std::filesystem;

nlohmann::json slice_json(const Slice& s) { return std::to_string(s.index) + "/" + std::to_string(s.count); }

}  // namespace

nlohmann::json effective_options_json(const std::vector<std::pair<std::string, EffectiveOptions>>& runs) {
  // A key is common when every point read it and all got the same value.
  std::map<std::string, std::pair<std::string, std::size_t>> seen;  // key -> (first value, points reading it)
  std::set<std::string> varying;
  for (const auto& [id, options] : runs)
    for (const auto& [key, value] : options) {
      const std::string text = yaml_to_string(value);
      auto [it, fresh] = seen.try_emplace(key, text, 0);
      if (!fresh && it->second.first != text) varying.insert(key);
      ++it->second.second;
    }
  for (const auto& [key, first_and_count] : seen)
    if (first_and_count.second != runs.size()) varying.insert(key);
  nlohmann::json common = nlohmann::json::object(), by_run = nlohmann::json::object();
  for (const auto& [id, options] : runs) {
    nlohmann::json own = nlohmann::json::object();
    for (const auto& [key, value] : options) {
      if (varying.count(key)) own[key] = yaml_to_json(value);
      else if (!common.contains(key)) common[key] = yaml_to_json(value);
    }
    if (!own.empty()) by_run[id] = std::move(own);
  }
  return {{"common", std::move(common)}, {"by_run", std::move(by_run)}};
}

RunJournal::RunJournal(const fs::path& dir, const SweepOptions& opt, const YAML::Node& root, const std::string& name,
                       const std::vector<std::string>& inputs, std::size_t planned, std::size_t already_done,
                       nlohmann::json effective_options)
    : path_(dir / "run.json") {
  if (fs::exists(path_)) {
    journal_ = read_json(path_.string());
  } else {
    journal_ = build_and_machine_info();
    journal_["name"] = name;
    journal_["config_file"] = opt.config_path;
    journal_["config"] = yaml_to_json(root);
    journal_["config_sha256"] = sha256_hex(YAML::Dump(root));
    journal_["seed"] = yaml_to_json(root["seed"]);
    journal_["threads_requested"] = yaml_to_json(root["threads"]);
    journal_["sessions"] = nlohmann::json::array();
    write_atomically(dir / "config.resolved.yaml", [&](std::ostream& os) { os << YAML::Dump(root) << '\n'; });
  }
  nlohmann::json hashes = nlohmann::json::object();
  for (const auto& f : inputs) hashes[f] = sha256_file_hex(f);
  nlohmann::json session = build_and_machine_info();
  session["started"] = utc_timestamp();
  session["argv"] = opt.argv;
  session["set"] = opt.sets;
  session["smoke"] = opt.smoke;
  session["filter"] = opt.filters;
  session["shard"] = slice_json(opt.shard);
  session["jobs"] = opt.jobs;
  session["resume"] = opt.resume;
  session["retry_failed"] = opt.retry_failed;
  session["input_sha256"] = hashes;
  session["runs_planned"] = planned;
  session["runs_already_done"] = already_done;
  session["effective_options"] = std::move(effective_options);
  journal_["sessions"].push_back(session);
  write_json(journal_, path_.string());
}

void RunJournal::close(int exit_status, std::size_t runs_done) {
  auto& session = journal_["sessions"].back();
  session["ended"] = utc_timestamp();
  session["exit_status"] = exit_status;
  session["runs_done"] = runs_done;
  write_json(journal_, path_.string());
}

}  // namespace fairshape
