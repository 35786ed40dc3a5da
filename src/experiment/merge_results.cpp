// `fairshape merge`: shards of one experiment joined into one folder (or CSV tables into one).
#include <filesystem>
#include <map>
#include <set>

#include <yaml-cpp/yaml.h>

#include "fairshape/core/error.h"
#include "fairshape/core/config.h"
#include "fairshape/experiment/run_metadata.h"
#include "fairshape/experiment/sweep_runner.h"
#include "fairshape/io/csv.h"
#include "fairshape/io/json_io.h"

namespace fairshape {
namespace fs = std::filesystem;
namespace {

// One experiment's shards have the same config.resolved.yaml (a shard's selection is not part of
// it); anything else is another experiment, whose rows would mix with no column saying which.
void check_same_experiment(const fs::path& first, const fs::path& config, const std::string& first_input,
                           const std::string& input) {
  const YAML::Node a = YAML::LoadFile(first.string()), b = YAML::LoadFile(config.string());
  if (yaml_to_string(a) == yaml_to_string(b)) return;
  std::vector<std::string> diff;
  differing_keys(a, b, "", diff, "in " + first_input, "in " + input);
  std::string keys;
  for (const auto& d : diff) keys += "\n  - " + d;
  throw InvalidInput(input + ": holds another experiment than " + first_input + " (their config.resolved.yaml differ; " +
                     "merge shards of one experiment only). Differing keys:" + keys);
}

// Columns united in first-seen order; each run's rows taken whole from the first input that
// has the run (so a table with many rows per run, like iterations.csv, keeps all of them).
// With `source`, a last column names the file each row came from, and every row is kept.
CsvTable merge_tables(const std::vector<fs::path>& inputs, bool source = false) {
  CsvTable out;
  std::vector<CsvTable> tables;
  for (const auto& in : inputs) {
    tables.push_back(read_csv(in.string(), true));
    if (tables.back().column("run_id") != 0)
      throw InvalidInput(in.string() + ": its first column is not run_id (not a fairshape table?)");
    for (const auto& h : tables.back().header)
      if (out.column(h) < 0) out.header.push_back(h);
  }
  if (source) {
    if (out.column("source") >= 0) throw InvalidInput("merge: the tables already have a 'source' column");
    out.header.push_back("source");
  }
  std::set<std::string> taken;
  for (std::size_t i = 0; i < tables.size(); ++i) {
    const CsvTable& t = tables[i];
    std::set<std::string> here;
    for (const auto& r : t.rows) {
      if (!source && taken.count(r[0])) continue;  // tables of unknown origin may share run ids
      here.insert(r[0]);
      std::vector<std::string> row(out.header.size());
      for (std::size_t c = 0; c < t.header.size(); ++c) row[out.column(t.header[c])] = r[c];
      if (source) row.back() = inputs[i].string();
      out.rows.push_back(std::move(row));
    }
    taken.insert(here.begin(), here.end());
  }
  return out;
}

void merge_folders(const std::vector<fs::path>& inputs, const fs::path& output) {
  const fs::path first_config = inputs.front() / "config.resolved.yaml";
  std::set<std::string> tables;
  nlohmann::json shards = nlohmann::json::array();
  for (const auto& in : inputs) {
    if (!fs::exists(in / "runs.csv")) throw InvalidInput(in.string() + ": no runs.csv (not a fairshape output folder?)");
    const fs::path config = in / "config.resolved.yaml";
    if (!fs::exists(config)) throw InvalidInput(in.string() + ": no config.resolved.yaml to check it against the others");
    check_same_experiment(first_config, config, inputs.front().string(), in.string());
    for (const auto& e : fs::directory_iterator(in))
      if (e.path().extension() == ".csv") tables.insert(e.path().filename().string());
    nlohmann::json shard{{"folder", fs::absolute(in).string()}};
    if (fs::exists(in / "run.json")) shard["run"] = read_json((in / "run.json").string());
    shards.push_back(shard);
  }
  fs::create_directories(output);
  for (const auto& name : tables) {
    std::vector<fs::path> present;
    for (const auto& in : inputs)
      if (fs::exists(in / name)) present.push_back(in / name);
    write_csv(merge_tables(present), (output / name).string());
  }
  fs::copy_file(first_config, output / "config.resolved.yaml", fs::copy_options::overwrite_existing);
  write_json({{"merged_at", utc_timestamp()}, {"shards", shards}}, (output / "run.json").string());
}

// Tables of one experiment are merged as its folders are; the experiment is told by the
// config.resolved.yaml beside each table. A table without one (copied elsewhere) cannot be
// told apart, so every row then says which file it came from.
void merge_csv_tables(const std::vector<fs::path>& inputs, const std::string& output) {
  bool all_configs = true;
  const fs::path* reference = nullptr;  // the first input with a config beside it
  for (const auto& in : inputs) {
    const fs::path config = in.parent_path() / "config.resolved.yaml";
    if (!fs::exists(config)) {
      all_configs = false;
      continue;
    }
    if (!reference) reference = &in;
    check_same_experiment(reference->parent_path() / "config.resolved.yaml", config, reference->string(), in.string());
  }
  write_csv(merge_tables(inputs, !all_configs), output);
}

}  // namespace

void merge_results(const std::vector<std::string>& inputs, const std::string& output) {
  if (inputs.empty()) throw InvalidConfig("merge: no input given");
  std::vector<fs::path> paths(inputs.begin(), inputs.end());
  const bool folders = fs::is_directory(paths.front());
  for (const auto& p : paths) {
    if (!fs::exists(p)) throw InvalidInput("merge: " + p.string() + ": no such file or folder");
    if (fs::is_directory(p) != folders)
      throw InvalidConfig("merge: give either output folders or CSV tables, not both (" + p.string() + ")");
  }
  if (folders) {
    if (fs::exists(output) && !fs::is_directory(output))
      throw InvalidConfig("merge: the output " + output + " must be a folder when merging folders");
    merge_folders(paths, output);
  } else {
    merge_csv_tables(paths, output);
  }
}

}  // namespace fairshape
