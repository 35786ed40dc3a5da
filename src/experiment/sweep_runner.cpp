#include "experiment/sweep_runner.h"

#include <spawn.h>
#include <sys/wait.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <iostream>
#include <set>

#include "core/atomic_file.h"
#include "core/config.h"
#include "core/error.h"
#include "experiment/config_loader.h"
#include "experiment/curve_run.h"
#include "experiment/feature_run.h"
#include "experiment/sheet_run.h"
#include "experiment/run_metadata.h"
#include "experiment/progress.h"
#include "experiment/run_one.h"
#include "experiment/sweep.h"
#include "io/csv.h"
#include "io/json_io.h"

extern char** environ;

namespace fairshape {
namespace fs = std::filesystem;
namespace {

struct Plan {
  YAML::Node root;
  std::string name;
  bool curve = false;  // curve runs (input.curve) or surface runs (input.mesh)
  bool sheet = false;  // B-spline sheet runs (sheets:)
  bool feature = false;  // feature-curve runs (features:)
  std::vector<std::string> search_dirs, columns;
  std::map<std::string, std::string> swept_key_of;  // CSV column -> swept key (they differ by a prefix)
  std::vector<RunPoint> runs;  // after --filter
};

bool passes_filters(const RunPoint& p, const std::vector<std::string>& filters) {
  for (const auto& f : filters) {
    const auto eq = f.find('=');
    if (eq == std::string::npos) throw InvalidConfig("--filter '" + f + "': expected key=value");
    const YAML::Node v = get_by_path(p.config, f.substr(0, eq));
    if (!v.IsDefined() || yaml_to_string(v) != f.substr(eq + 1)) return false;
  }
  return true;
}

// Loads, expands and validates every run; all problems are reported together.
Plan make_plan(const SweepOptions& opt) {
  Plan plan;
  plan.root = load_experiment_config(opt.config_path, opt.sets);
  plan.search_dirs = input_search_dirs(opt.config_path);
  plan.curve = is_curve_config(plan.root);
  plan.sheet = is_sheet_config(plan.root);
  plan.feature = is_feature_config(plan.root);
  std::set<std::string> problems;
  for (auto& p : expand_sweep(plan.root)) {
    try {
      plan.name = plan.feature ? FeatureRunSpec::from_config(p.config, plan.search_dirs).name
                  : plan.sheet ? SheetRunSpec::from_config(p.config).name
                  : plan.curve ? CurveRunSpec::from_config(p.config, plan.search_dirs).name
                               : RunSpec::from_config(p.config, components(), plan.search_dirs).name;
    } catch (const InvalidConfig& e) {
      problems.insert(e.what());
      continue;
    } catch (const YAML::Exception& e) {
      problems.insert(std::string("YAML: ") + e.what());
      continue;
    }
    if (passes_filters(p, opt.filters)) plan.runs.push_back(std::move(p));
  }
  if (!problems.empty()) {
    std::string msg = opt.config_path + ": " + std::to_string(problems.size()) + " problem(s), nothing was run:";
    for (const auto& p : problems) msg += "\n  - " + p;
    throw InvalidConfig(msg);
  }
  plan.columns = {"run_id"};
  const auto& metrics = plan.feature ? feature_metric_columns() : plan.sheet ? sheet_metric_columns() : plan.curve ? curve_metric_columns() : metric_columns();
  for (const auto& k : swept_keys(plan.root)) {  // a swept key named like a metric (energy) gets a prefix
    plan.columns.push_back(std::find(metrics.begin(), metrics.end(), k) == metrics.end() ? k : "param." + k);
    plan.swept_key_of[plan.columns.back()] = k;
  }
  for (const char* k : {"implementation", "solver.type"})
    if (std::find(plan.columns.begin(), plan.columns.end(), k) == plan.columns.end()) plan.columns.push_back(k);
  for (const auto& m : metrics) plan.columns.push_back(m);
  return plan;
}

std::string default_out_dir(const std::string& name) {
  const fs::path base = fs::path("results") / name;
  const fs::path dir = base / (utc_timestamp("%Y%m%d-%H%M%S") + "_" + git_short_sha());
  fs::create_directories(dir);
  const fs::path link = base / "latest";
  std::error_code ec;
  fs::remove(link, ec);
  fs::create_directory_symlink(dir.filename(), link, ec);
  return dir.string();
}

// Prepares the folder; returns the run_ids already finished there (for --resume).
std::set<std::string> prepare_out_dir(const SweepOptions& opt, const Plan& plan, const std::string& dir) {
  const fs::path runs_csv = fs::path(dir) / "runs.csv";
  if (fs::exists(runs_csv) && !opt.resume) {
    if (!opt.force)
      throw InvalidConfig(dir + " already holds results (runs.csv): use --resume to continue or --force to start over");
    for (const char* f : {"runs.csv", "iterations.csv", "steps.csv", "cells.csv", "run.json", "config.resolved.yaml", "final.obj"})
      fs::remove(fs::path(dir) / f);
    fs::remove_all(fs::path(dir) / "vtk");
    fs::remove_all(fs::path(dir) / "curves");
    fs::remove_all(fs::path(dir) / "final");
  }
  fs::create_directories(fs::path(dir) / "vtk");
  std::set<std::string> done;
  if (fs::exists(runs_csv)) {
    truncate_partial_tail(runs_csv.string());
    const CsvTable t = read_csv(runs_csv.string());
    if (t.header != plan.columns)
      throw InvalidConfig(runs_csv.string() + ": its columns differ from this config's; resume it with the same "
                          "config and --set options, or use another --out");
    for (const auto& r : t.rows) done.insert(r[0]);
  } else if (opt.worker.count == 1) {
    write_atomically(runs_csv, [&](std::ostream& os) { os << csv_record(plan.columns); });
  }
  const fs::path it_csv = fs::path(dir) / "iterations.csv";
  if (fs::exists(it_csv)) truncate_partial_tail(it_csv.string());
  else write_atomically(it_csv, [](std::ostream& os) { os << csv_record({"run_id", "iteration", "residual", "energy", "seconds", "error_vs_reference"}); });
  const fs::path steps_csv = fs::path(dir) / "steps.csv";
  if (fs::exists(steps_csv)) truncate_partial_tail(steps_csv.string());
  else write_atomically(steps_csv, [&](std::ostream& os) { os << csv_record(plan.sheet ? sheet_step_columns() : plan.curve ? curve_step_columns() : step_columns()); });
  return done;
}

void write_metadata(const SweepOptions& opt, const Plan& plan, const std::string& dir, const std::string& started,
                    const std::string& ended) {
  nlohmann::json j = build_and_machine_info();
  j["name"] = plan.name;
  j["config_file"] = opt.config_path;
  j["set"] = opt.sets;
  j["seed"] = yaml_to_json(plan.root["seed"]);
  j["threads_requested"] = yaml_to_json(plan.root["threads"]);
  j["runs_planned"] = plan.runs.size();
  j["started"] = started;
  if (!ended.empty()) j["ended"] = ended;
  j["config"] = yaml_to_json(plan.root);
  write_json(j, (fs::path(dir) / "run.json").string());
  write_atomically(fs::path(dir) / "config.resolved.yaml",
                   [&](std::ostream& os) { os << YAML::Dump(plan.root) << '\n'; });
}

// `m` carries the metrics plus implementation and solver.type.
std::vector<std::string> row_fields(const Plan& plan, const RunPoint& p, const MetricRow& m) {
  std::vector<std::string> out;
  for (const auto& c : plan.columns) {
    if (c == "run_id") out.push_back(p.run_id);
    else if (m.count(c)) out.push_back(m.at(c));
    else out.push_back(yaml_to_string(get_by_path(p.config, plan.swept_key_of.at(c))));
  }
  return out;
}

std::unique_ptr<tbb::global_control> limit_threads(int threads) {
  if (threads <= 0) return nullptr;
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
}

MetricRow execute_surface(const RunPoint& p, const Plan& plan, RunCache& cache, const std::string& dir, bool single) {
  RunSpec spec = RunSpec::from_config(p.config, components(), plan.search_dirs);
  const auto threads = limit_threads(spec.threads);
  MetricRow m = execute_run(spec, cache, {dir, p.run_id, single});
  m["implementation"] = std::string(to_string(spec.implementation));
  m["solver.type"] = spec.solver_type;
  return m;
}

MetricRow execute_curve(const RunPoint& p, const Plan& plan, const std::string& dir, bool single) {
  CurveRunSpec spec = CurveRunSpec::from_config(p.config, plan.search_dirs);
  const auto threads = limit_threads(spec.threads);
  return execute_curve_run(spec, {dir, p.run_id, single});
}

MetricRow execute_feature(const RunPoint& p, const Plan& plan, const std::string& dir, bool single) {
  FeatureRunSpec spec = FeatureRunSpec::from_config(p.config, plan.search_dirs);
  const auto threads = limit_threads(spec.threads);
  return execute_feature_run(spec, {dir, p.run_id, single});
}

MetricRow execute_sheet(const RunPoint& p, const std::string& dir, bool single) {
  SheetRunSpec spec = SheetRunSpec::from_config(p.config);
  const auto threads = limit_threads(spec.threads);
  return execute_sheet_run(spec, {dir, p.run_id, single});
}

int run_in_process(const SweepOptions& opt, const Plan& plan, const std::vector<const RunPoint*>& todo,
                   const std::string& dir) {
  CsvAppender rows((fs::path(dir) / "runs.csv").string());
  RunCache cache;
  const std::string prefix = opt.worker.count > 1 ? "[worker " + std::to_string(opt.worker.index) + "] " : "";
  Progress progress(static_cast<int>(todo.size()), prefix);
  int failed = 0, done = 0;
  const bool single = plan.runs.size() == 1;
  for (const RunPoint* p : todo) {
    const MetricRow m = plan.feature ? execute_feature(*p, plan, dir, single)
                        : plan.sheet ? execute_sheet(*p, dir, single)
                        : plan.curve ? execute_curve(*p, plan, dir, single)
                                     : execute_surface(*p, plan, cache, dir, single);
    rows.append(row_fields(plan, *p, m));
    const std::string& term = m.at("termination");
    if (term != "converged" && term != "max_iterations") {
      ++failed;
      std::cerr << prefix << "run " << p->run_id << " " << term << ": " << m.at("message") << "\n";
    }
    progress.finished(++done, p->run_id, term, std::stod(m.at("time_s")));
  }
  progress.close();
  return failed ? 3 : 0;
}

int spawn_workers(const SweepOptions& opt, const std::string& dir) {
  std::vector<pid_t> pids;
  for (int w = 0; w < opt.jobs; ++w) {
    std::vector<std::string> args{opt.executable, "run", opt.config_path, "--out", dir, "--resume",
                                  "--worker", std::to_string(w) + "/" + std::to_string(opt.jobs),
                                  "--shard", std::to_string(opt.shard.index) + "/" + std::to_string(opt.shard.count)};
    for (const auto& s : opt.sets) args.insert(args.end(), {"--set", s});
    for (const auto& f : opt.filters) args.insert(args.end(), {"--filter", f});
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid;
    if (posix_spawn(&pid, opt.executable.c_str(), nullptr, nullptr, argv.data(), environ) != 0)
      throw Error("cannot start worker process " + opt.executable);
    pids.push_back(pid);
  }
  int worst = 0;
  for (pid_t pid : pids) {
    int status = 0;
    waitpid(pid, &status, 0);
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 4;
    worst = std::max(worst, code);
  }
  return worst;
}

}  // namespace

Slice Slice::parse(const std::string& text, const std::string& option) {
  Slice s;
  const auto slash = text.find('/');
  try {
    if (slash == std::string::npos) throw std::invalid_argument("");
    s.index = std::stoi(text.substr(0, slash));
    s.count = std::stoi(text.substr(slash + 1));
  } catch (const std::exception&) {
    throw InvalidConfig(option + " '" + text + "': expected i/n, e.g. 0/4");
  }
  if (s.count < 1 || s.index < 0 || s.index >= s.count)
    throw InvalidConfig(option + " '" + text + "': need 0 <= i < n");
  return s;
}

int run_sweep(const SweepOptions& opt) {
  const Plan plan = make_plan(opt);
  const bool is_worker = opt.worker.count > 1;
  const std::string dir = !opt.out_dir.empty() ? opt.out_dir : default_out_dir(plan.name);
  fs::create_directories(dir);
  const std::set<std::string> done = prepare_out_dir(opt, plan, dir);
  const std::string started = utc_timestamp();
  if (!is_worker) write_metadata(opt, plan, dir, started, "");

  std::vector<const RunPoint*> todo;
  int position = 0;
  for (const auto& p : plan.runs) {
    if (p.index % opt.shard.count != opt.shard.index) continue;
    if (position++ % opt.worker.count != opt.worker.index) continue;
    if (!done.count(p.run_id)) todo.push_back(&p);
  }
  if (!is_worker)
    std::cerr << plan.name << ": " << plan.runs.size() << " run(s) in the sweep, " << todo.size()
              << " to do here" << (done.empty() ? "" : " (" + std::to_string(done.size()) + " already done)")
              << " -> " << dir << "\n";
  const int status = opt.jobs > 1 && !is_worker ? spawn_workers(opt, dir) : run_in_process(opt, plan, todo, dir);
  if (!is_worker) write_metadata(opt, plan, dir, started, utc_timestamp());
  return status;
}

void merge_run_tables(const std::vector<std::string>& inputs, const std::string& output) {
  if (inputs.empty()) throw InvalidConfig("merge: no input CSV given");
  CsvTable out;
  std::vector<CsvTable> tables;
  for (const auto& in : inputs) {
    tables.push_back(read_csv(in, true));
    if (tables.back().column("run_id") < 0) throw InvalidInput(in + ": no run_id column (not a runs.csv?)");
    for (const auto& h : tables.back().header)
      if (out.column(h) < 0) out.header.push_back(h);
  }
  std::set<std::string> seen;
  for (const auto& t : tables) {
    const int id_col = t.column("run_id");
    for (const auto& r : t.rows) {
      if (!seen.insert(r[id_col]).second) continue;
      std::vector<std::string> row(out.header.size());
      for (std::size_t c = 0; c < t.header.size(); ++c) row[out.column(t.header[c])] = r[c];
      out.rows.push_back(std::move(row));
    }
  }
  write_csv(out, output);
}

}  // namespace fairshape
