#include "fairshape/experiment/run_basics.h"

#include "fairshape/core/summary.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>

#include "fairshape/io/mesh_io.h"

namespace fairshape {
namespace fs = std::filesystem;

std::string resolve_input(const std::string& path, const std::vector<std::string>& dirs, const std::string& key) {
  std::error_code ec;
  if (fs::path(path).is_absolute()) {
    if (fs::is_regular_file(path, ec)) return path;
    if (fs::exists(path, ec))
      throw InvalidConfig(key + ": '" + path + "' is not a regular file (a device, FIFO or folder)");
  } else {
    for (const auto& d : dirs)
      if (fs::is_regular_file(fs::path(d) / path)) return (fs::path(d) / path).lexically_normal().string();
  }
  throw InvalidConfig(key + ": input file '" + path + "' not found (looked in the current directory and "
                      "beside the config)");
}

std::string read_input_path(Config& block, const std::string& key, const std::string& doc, const std::vector<std::string>& dirs) {
  const std::string given = block.require<std::string>(key, doc);
  return block.documenting() ? given : resolve_input(given, dirs, block.key_path(key));
}

Vec3 read_vec3(Config& c, const std::string& key, const Vec3& fallback, const std::string& doc) {
  const std::vector<double> v = c.get<std::vector<double>>(key, {fallback.x(), fallback.y(), fallback.z()}, doc);
  if (v.size() != 3 || !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
    throw InvalidConfig(c.key_path(key) + ": expected three finite numbers [x, y, z]");
  return {v[0], v[1], v[2]};
}

std::vector<std::string> input_search_dirs(const std::string& config_path) {
  std::vector<std::string> dirs{"."};
  for (fs::path p = fs::absolute(config_path).parent_path(); !p.empty(); p = p.parent_path()) {
    dirs.push_back(p.string());
    if (p == p.root_path()) break;
  }
  return dirs;
}

void RunBasics::note_unused(const Config& block, const std::string& key, bool used) {
  if (!used && block.has(key)) unused_keys.push_back(block.key_path(key));
}

void RunBasics::note_unused(const Config& block) {
  if (block.node().IsMap())
    for (const auto& kv : block.node()) unused_keys.push_back(block.key_path(kv.first.as<std::string>()));
}

std::string RunBasics::unused_keys_cell() const {
  std::string out;
  for (const auto& k : unused_keys) out.append(out.empty() ? "" : " ").append(k);
  return out;
}

RunBasics read_run_basics(Config& root) {
  RunBasics b;
  b.name = root.require<std::string>("name", "experiment name (names the results folder)");
  // The name becomes results/<name>/: one plain folder name, so no output can land elsewhere.
  const bool plain = !b.name.empty() && b.name.size() <= 128 && b.name != "." && b.name != ".." &&
                     b.name.front() != '.' && b.name.find_first_not_of(
                         "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789._-") == std::string::npos;
  if (!plain && !root.documenting())
    throw InvalidConfig("name: '" + b.name + "' must be a plain folder name (letters, digits, '.', '_', '-'; not "
                        "starting with '.'; at most 128 characters): it names results/<name>/");
  root.get<std::string>("description", "", "free text");
  b.seed = root.get_int("seed", 0, 0, INT32_MAX, "random seed (runs without randomness ignore it)");
  b.threads = root.get_int("threads", 0, 0, 4096, "TBB threads for optimized back ends (0 = all cores)");
  (void)root.get_int("repeat", 1, 1, 1000, "timing repeats, run by the harness (every timing column from the median execution by time_s, solve_min_s the minimum)");
  std::vector<std::string> outcomes{"success"};
  for (const std::string& t : termination_names())
    if (!is_success(termination_from_string(t))) outcomes.push_back(t);
  (void)root.get_choice("expect", "success", outcomes,
                        "the outcome the run is meant to show, checked by the harness: success, or the termination of a "
                        "failure it demonstrates (Figure 2's thin plate without boundary constraints folds); any other "
                        "outcome fails the run");
  b.implementation = root.get_enum("implementation", Backend::Optimized, backend_names(), "back end of every component");
  return b;
}

void require_readable_mesh(const std::string& path, const std::string& key) {
  static std::mutex guard;
  static std::map<std::string, std::string> problems;  // path -> the reader's message ("" when readable)
  std::lock_guard<std::mutex> lock(guard);
  auto it = problems.find(path);
  if (it == problems.end()) {
    std::string problem;
    try {
      (void)read_mesh(path);
    } catch (const Error& e) {
      problem = e.what();
    }
    it = problems.emplace(path, problem).first;
  }
  if (!it->second.empty()) throw InvalidConfig(key + ": " + it->second);
}

}  // namespace fairshape
