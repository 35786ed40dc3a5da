#include "fairshape/experiment/sweep_runner.h"

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <stdexcept>

#include "fairshape/core/atomic_file.h"
#include "fairshape/core/config.h"
#include "fairshape/core/error.h"
#include "fairshape/core/memory.h"
#include "fairshape/core/summary.h"
#include "fairshape/core/timer.h"
#include "fairshape/experiment/config_loader.h"
#include "fairshape/experiment/output_folder.h"
#include "fairshape/experiment/progress.h"
#include "fairshape/experiment/run_kind.h"
#include "fairshape/experiment/run_metadata.h"
#include "fairshape/experiment/run_basics.h"
#include "fairshape/experiment/supervisor.h"
#include "fairshape/experiment/sweep.h"

namespace fairshape {
namespace fs = std::filesystem;
namespace {

struct Filter {
  std::string key, value;
};

struct Plan {
  YAML::Node root;
  std::vector<std::string> notes;  // what the --set options replaced
  std::vector<std::string> search_dirs;
  std::vector<std::unique_ptr<RunKind>> kinds;
  RunKind* kind = nullptr;
  std::unique_ptr<SweepSpace> space;
  std::vector<Filter> filters;
  TableLayout layout;
  std::map<std::string, std::string> swept_key_of;  // column -> swept key (they differ by a prefix)
  std::string name;
  std::vector<std::string> input_files;
  std::vector<std::size_t> selected;  // flat indices of this process's points, in order
  // What each validated point's reads returned, defaults included (run.json's effective_options).
  std::vector<std::pair<std::string, EffectiveOptions>> effective;
};

std::vector<Filter> parse_filters(const std::vector<std::string>& filters, const std::vector<std::string>& swept) {
  std::vector<Filter> out;
  for (const auto& f : filters) {
    const auto eq = f.find('=');
    if (eq == std::string::npos || eq == 0) throw InvalidConfig("--filter '" + f + "': expected key=value");
    Filter flt{f.substr(0, eq), f.substr(eq + 1)};
    if (std::find(swept.begin(), swept.end(), flt.key) == swept.end()) {
      std::string valid;
      for (const auto& k : swept) valid += (valid.empty() ? "" : ", ") + k;
      throw InvalidConfig("--filter " + flt.key + ": not a swept key (swept: " + (valid.empty() ? "none" : valid) + ")");
    }
    out.push_back(std::move(flt));
  }
  return out;
}

bool passes(const std::vector<std::pair<std::string, std::string>>& params, const std::vector<Filter>& filters) {
  for (const auto& f : filters) {
    const auto it = std::find_if(params.begin(), params.end(), [&](const auto& kv) { return kv.first == f.key; });
    if (it == params.end() || it->second != f.value) return false;
  }
  return true;
}

// Validating a large sweep takes a while (every point's config is parsed and checked; the
// hierarchies once per distinct system): on a terminal or in a log, say how far it is.
class ValidationProgress {
 public:
  explicit ValidationProgress(std::size_t total) : total_(total) {}
  void step(std::size_t problems) {
    ++done_;
    if (total_ < 10000 || clock_.seconds() < next_) return;
    next_ = clock_.seconds() + 2.0;
    std::cerr << "fairshape: validating the sweep: " << done_ << " of " << total_ << " point(s), " << problems
              << " problem(s) so far\n";
  }

 private:
  std::size_t total_, done_ = 0;
  Timer clock_;
  double next_ = 2.0;  // the first line after two seconds
};

TableLayout layout_of(const RunKind& kind, const std::vector<std::string>& swept,
                      std::map<std::string, std::string>& swept_key_of) {
  TableLayout l;
  std::set<std::string> taken(kind.metric_columns().begin(), kind.metric_columns().end());
  for (const auto& t : kind.tables()) taken.insert(t.columns.begin(), t.columns.end());
  l.key_columns = {"run_id"};
  for (const auto& k : swept) {  // a swept key named like a column (energy) gets a prefix
    const std::string column = taken.count(k) ? "param." + k : k;
    l.key_columns.push_back(column);
    swept_key_of[column] = k;
  }
  for (const auto& k : kind.identity_columns())
    if (std::find(l.key_columns.begin(), l.key_columns.end(), k) == l.key_columns.end()) l.key_columns.push_back(k);
  l.runs_columns = l.key_columns;
  for (const auto& m : kind.metric_columns())
    if (std::find(l.key_columns.begin(), l.key_columns.end(), m) == l.key_columns.end()) l.runs_columns.push_back(m);
  for (const auto& t : kind.tables()) {
    TableSchema s{t.name, l.key_columns};
    s.columns.insert(s.columns.end(), t.columns.begin(), t.columns.end());
    l.tables.push_back(std::move(s));
  }
  return l;
}

// "(points 0, 3, 5)": where in a sweep a problem is; the first few of many.
std::string point_list(const std::vector<std::size_t>& points, std::size_t sweep_size) {
  std::string s = "(";
  if (points.size() == sweep_size) return s.append("all ").append(std::to_string(sweep_size)).append(" points)");
  constexpr std::size_t kShown = 8;
  s += points.size() == 1 ? "point " : "points ";
  for (std::size_t k = 0; k < std::min(points.size(), kShown); ++k) {
    if (k) s += ", ";
    s += std::to_string(points[k]);
  }
  if (points.size() > kShown) s.append(" and ").append(std::to_string(points.size() - kShown)).append(" more");
  return s + ")";
}

// Loads the config, picks this process's points and, in the supervisor, validates each of
// them (all problems reported together, before anything runs).
Plan make_plan(const SweepOptions& opt, bool validate) {
  Plan plan;
  plan.root = load_experiment_config(opt.config_path, opt.sets, &plan.notes,
                                     opt.smoke ? ConfigVariant::Smoke : ConfigVariant::Full);
  plan.search_dirs = input_search_dirs(opt.config_path);
  plan.kinds = make_run_kinds();
  plan.space = std::make_unique<SweepSpace>(plan.root);
  plan.filters = parse_filters(opt.filters, plan.space->keys());
  std::map<std::string, std::vector<std::size_t>> problems;  // message -> the points that have it
  std::set<std::string> inputs;
  std::size_t position = 0;
  ValidationProgress progress(validate ? (plan.space->size() - opt.shard.index + opt.shard.count - 1) / opt.shard.count : 0);
  for (std::size_t i = opt.shard.index; i < plan.space->size(); i += opt.shard.count) {
    progress.step(problems.size());
    if (!plan.filters.empty() && !passes(plan.space->params(i), plan.filters)) continue;
    if (position++ % opt.worker.count != static_cast<std::size_t>(opt.worker.index)) continue;
    plan.selected.push_back(i);
    if (!validate && plan.kind) continue;
    const RunPoint p = plan.space->point(i);
    try {
      RunKind& kind = kind_of(p.config, plan.kinds);
      if (plan.kind && plan.kind != &kind)
        throw InvalidConfig("point " + std::to_string(i) + " is a " + kind.name() + " run but point " +
                            std::to_string(plan.selected.front()) + " is a " + plan.kind->name() +
                            " run: one experiment holds one kind of run");
      plan.kind = &kind;
      if (!validate) continue;
      EffectiveOptions used;
      const ValidatedRun v = [&] {
        RecordEffectiveOptions record(used);
        return kind.validate(p.config, plan.search_dirs);
      }();
      plan.effective.emplace_back(p.run_id, std::move(used));
      if (plan.name.empty()) plan.name = v.name;
      inputs.insert(v.input_files.begin(), v.input_files.end());
    } catch (const InvalidConfig& e) {
      problems[e.what()].push_back(i);
    } catch (const YAML::Exception& e) {
      problems[std::string("YAML: ") + e.what()].push_back(i);
    }
  }
  for (auto& kind : plan.kinds) kind->validation_done();
  // Validation may have built hierarchies as large as a run's; a supervisor must not hold them
  // (freed but resident) while its workers run.
  release_free_memory();
  if (!problems.empty()) {
    std::string msg = opt.config_path + ": " + std::to_string(problems.size()) + " problem(s), nothing was run:";
    for (const auto& [problem, points] : problems) {
      msg.append("\n  - ").append(problem);
      if (plan.space->size() > 1) msg.append(" ").append(point_list(points, plan.space->size()));
    }
    throw InvalidConfig(msg);
  }
  if (plan.selected.empty() && !opt.is_worker)
    throw InvalidConfig(opt.config_path + ": no point of the sweep " +
                        (opt.filters.empty() ? std::string("falls in --shard ") + std::to_string(opt.shard.index) + "/" +
                                                   std::to_string(opt.shard.count)
                                             : std::string("passes the --filter options")) +
                        ": nothing to run");
  if (!plan.kind) plan.kind = &kind_of(plan.space->point(0).config, plan.kinds);  // a worker with no point
  plan.input_files.assign(inputs.begin(), inputs.end());
  plan.layout = layout_of(*plan.kind, plan.space->keys(), plan.swept_key_of);
  return plan;
}

std::string value_at(const YAML::Node& config, const std::string& key) {
  const YAML::Node v = get_by_path(config, key);
  return v.IsDefined() ? yaml_to_string(v) : "";
}

std::vector<std::string> key_fields(const Plan& plan, const RunPoint& p, const MetricRow& m) {
  std::vector<std::string> out;
  for (const auto& c : plan.layout.key_columns) {
    if (c == "run_id") out.push_back(p.run_id);
    else if (const auto s = plan.swept_key_of.find(c); s != plan.swept_key_of.end()) out.push_back(value_at(p.config, s->second));
    else if (const auto v = m.find(c); v != m.end()) out.push_back(v->second);
    else out.push_back(value_at(p.config, c));
  }
  return out;
}

std::vector<std::string> runs_row(const Plan& plan, const std::vector<std::string>& keys, const MetricRow& m) {
  std::vector<std::string> out = keys;
  for (std::size_t c = keys.size(); c < plan.layout.runs_columns.size(); ++c) {
    const auto it = m.find(plan.layout.runs_columns[c]);
    out.push_back(it == m.end() ? "" : it->second);
  }
  return out;
}

MetricRow crashed_row(const std::string& message) {
  return {{"termination", std::string(to_string(Termination::Crashed))}, {"message", message}};
}

fs::path marker_of(const fs::path& dir, int worker) {
  return dir / ".fairshape" / ("worker-" + std::to_string(worker) + ".run");
}

// A testing aid (documented in configs/README.md): FAIRSHAPE_FAULT_INJECTION=length_error@K
// or segv@K makes the run at sweep index K throw std::length_error or raise SIGSEGV.
void inject_fault(std::size_t index) {
  const char* spec = std::getenv("FAIRSHAPE_FAULT_INJECTION");
  if (!spec) return;
  const std::string s = spec;
  const auto at = s.find('@');
  if (at == std::string::npos || s.substr(at + 1) != std::to_string(index)) return;
  if (s.compare(0, at, "length_error") == 0) throw std::length_error("fault injection: std::length_error");
  if (s.compare(0, at, "segv") == 0) std::raise(SIGSEGV);
}

bool succeeded(const MetricRow& m) {
  const auto it = m.find("termination");
  if (it == m.end()) return false;
  try {
    return is_success(termination_from_string(it->second));
  } catch (const Error&) {
    return false;
  }
}

// The run delivered what its config's `expect` asks: success by default, or the named failure
// of a run that demonstrates one (a row ending otherwise — even a success — is a failed run).
bool as_expected(const MetricRow& m, const YAML::Node& config) {
  const std::string expect = config["expect"] ? config["expect"].as<std::string>() : "success";
  if (expect == "success") return succeeded(m);
  const auto it = m.find("termination");
  return it != m.end() && it->second == expect;
}

// No NaN or infinity in a row marked a success: a run whose metrics are not finite (an
// offset of 1e308, a diverged iterate that still met its stopping rule) failed numerically.
MetricRow with_finite_metrics(MetricRow m) {
  if (!succeeded(m)) return m;
  std::string bad;
  for (const auto& [column, value] : m) {
    std::string v = value;
    if (!v.empty() && (v[0] == '-' || v[0] == '+')) v.erase(0, 1);
    if (v == "nan" || v == "inf") bad.append(bad.empty() ? "" : ", ").append(column);
  }
  if (bad.empty()) return m;
  m["termination"] = std::string(to_string(Termination::NumericalFailure));
  m["message"] = "non-finite " + bad + (m["message"].empty() ? "" : "; " + m["message"]);
  return m;
}

MetricRow execute_guarded(Plan& plan, const RunPoint& p, const RunOutputs& out) {
  try {
    inject_fault(p.index);
    // `repeat` was validated with the run (1..1000) by its kind.
    const int repeat = p.config["repeat"] ? p.config["repeat"].as<int>() : 1;
    return with_finite_metrics(run_repeated(
        repeat, plan.kind->measured_columns(), out,
        [&](const RunOutputs& o) { return plan.kind->execute(p.config, plan.search_dirs, o); }, succeeded));
  } catch (const std::bad_alloc&) {
    return crashed_row("out of memory (std::bad_alloc)");
  } catch (const Error& e) {  // a kind lets its own errors through only by mistake
    return crashed_row(std::string("unhandled fairshape error: ") + e.what());
  } catch (const std::exception& e) {
    return crashed_row(std::string("unexpected exception: ") + e.what());
  } catch (...) {
    return crashed_row("unexpected exception of unknown type");
  }
}

// Runs the plan's points that have no row yet in `dir`, committing each run's rows together:
// a worker's loop, or the whole run's with --in-process. \return 3 if a run failed, else 0.
int run_points(Plan& plan, const SweepOptions& opt, const fs::path& dir) {
  const std::set<std::string> done = recorded_runs(dir);
  std::vector<std::size_t> todo;  // points are built one at a time: a sweep's configs do not all fit
  for (std::size_t i : plan.selected)
    if (!done.count(plan.space->run_id(i))) todo.push_back(i);
  const std::string prefix = opt.worker.count > 1 ? "[worker " + std::to_string(opt.worker.index) + "] " : "";
  Progress progress(static_cast<int>(todo.size()), prefix);
  const bool single = plan.space->size() == 1;
  const fs::path marker = marker_of(dir, opt.worker.index);
  int failed = 0, finished = 0;
  for (std::size_t index : todo) {
    const RunPoint p = plan.space->point(index);
    write_atomically(marker, [&](std::ostream& os) { os << p.run_id << "\n"; });
    RunTables tables;
    const RunOutputs out{dir.string(), p.run_id, single, &tables};
    const MetricRow m = execute_guarded(plan, p, out);
    const auto keys = key_fields(plan, p, m);
    commit_run(dir, plan.layout, keys, runs_row(plan, keys, m), tables);
    fs::remove(marker);
    const std::string& term = m.at("termination");
    if (!as_expected(m, p.config)) {
      ++failed;
      std::cerr << prefix << "run " << p.run_id << " " << term << (succeeded(m) ? " (expected " + p.config["expect"].as<std::string>() + ")" : "")
                << ": " << m.at("message") << "\n";
    } else if (!succeeded(m)) {
      std::cerr << prefix << "run " << p.run_id << " " << term << ", as expected: " << m.at("message") << "\n";
    }
    const auto t = m.find("time_s");
    progress.finished(++finished, p.run_id, term, t == m.end() || t->second.empty() ? 0.0 : std::stod(t->second));
  }
  progress.close();
  return failed ? 3 : 0;
}

// A worker process the supervisor started.
int run_worker(const SweepOptions& opt) {
  bind_worker_to_supervisor();
  Plan plan = make_plan(opt, false);
  return run_points(plan, opt, opt.out_dir);
}

}  // namespace

void differing_keys(const YAML::Node& a, const YAML::Node& b, const std::string& path, std::vector<std::string>& out,
                    const std::string& in_a, const std::string& in_b) {
  if (a.IsMap() && b.IsMap()) {
    std::set<std::string> keys;
    for (const auto& kv : a) keys.insert(kv.first.as<std::string>());
    for (const auto& kv : b) keys.insert(kv.first.as<std::string>());
    for (const auto& k : keys) differing_keys(a[k], b[k], path.empty() ? k : path + "." + k, out, in_a, in_b);
    return;
  }
  const std::string sa = a.IsDefined() ? yaml_to_string(a) : "(absent)", sb = b.IsDefined() ? yaml_to_string(b) : "(absent)";
  if (sa != sb) out.push_back(path + " (" + sa + " " + in_a + ", " + sb + " " + in_b + ")");
}

namespace {

// A resume continues the same experiment: its configuration outside `sweep` must be the one
// the folder was started with (the sweep may grow: new points simply run).
void check_same_experiment(const fs::path& dir, const YAML::Node& root) {
  const fs::path stored = dir / "config.resolved.yaml";
  if (!fs::exists(stored)) return;
  YAML::Node before = YAML::LoadFile(stored.string());
  YAML::Node now = YAML::Clone(root);
  before.remove("sweep");
  now.remove("sweep");
  std::vector<std::string> diff;
  differing_keys(before, now, "", diff);
  if (diff.empty()) return;
  std::string msg = dir.string() + " holds another experiment; --resume needs the same config and --set options. "
                                   "Differing keys:";
  for (const auto& d : diff) msg += "\n  - " + d;
  throw InvalidConfig(msg + "\nUse another --out for the changed experiment.");
}

// What the harness keeps only while runs execute: temporaries and the run-in-progress markers.
void remove_run_markers(const OutputFolder& folder, const fs::path& dir) {
  folder.remove_temporaries();
  fs::remove_all(dir / ".fairshape");
}

int supervise(const SweepOptions& opt) {
  Plan plan = make_plan(opt, true);
  for (const auto& n : plan.notes) std::cerr << "fairshape: " << n << "\n";
  if (opt.dry_run) {
    std::cout << plan.selected.size() << " of " << plan.space->size() << " point(s) (" << plan.kind->name()
              << " runs):\n";
    for (std::size_t i : plan.selected) {
      std::cout << "  " << i << "  " << plan.space->run_id(i);
      for (const auto& [k, v] : plan.space->params(i)) std::cout << "  " << k << "=" << v;
      std::cout << "\n";
    }
    return 0;
  }
  const fs::path dir = !opt.out_dir.empty() ? fs::path(opt.out_dir) : default_out_dir(plan.name);
  OutputFolder folder(dir);
  if (fs::exists(folder.runs_csv()) && !opt.resume) {
    if (!opt.force)
      throw InvalidConfig(dir.string() + " already holds results (runs.csv): use --resume to continue or --force to start over");
    folder.clear_results();
  }
  if (opt.resume) check_same_experiment(dir, plan.root);
  folder.remove_temporaries();
  fs::remove_all(dir / ".fairshape");
  fs::create_directories(dir / ".fairshape");
  create_run_folders(dir.string());
  if (opt.retry_failed) {
    const std::size_t n = folder.drop_failed_runs();
    std::cerr << "fairshape: --retry-failed: " << n << " failed run(s) will run again\n";
  } else if (opt.resume) {
    // A run whose outputs could not be written (disk full) never finished: run it again.
    if (const std::size_t n = folder.drop_failed_runs(true))
      std::cerr << "fairshape: " << n << " run(s) whose outputs could not be written will run again\n";
  }
  folder.roll_back_orphan_rows(plan.layout);
  const std::set<std::string> done = folder.finished_runs(plan.layout);
  std::size_t todo = 0;
  for (std::size_t i : plan.selected)
    if (!done.count(plan.space->run_id(i))) ++todo;
  RunJournal journal(dir, opt, plan.root, plan.name, plan.input_files, plan.selected.size(), done.size(),
                     effective_options_json(plan.effective));
  std::cerr << plan.name << ": " << plan.space->size() << " run(s) in the sweep, " << todo << " to do here"
            << (done.empty() ? "" : " (" + std::to_string(done.size()) + " already done)") << " -> " << dir.string()
            << "\n";

  if (opt.in_process) {
    // No supervisor, so a crash ends the command: the rows committed before it stay and
    // --resume runs the rest (the folder's lock is released with the process).
    const int status = run_points(plan, opt, dir);
    remove_run_markers(folder, dir);
    journal.close(status, folder.finished_runs(plan.layout).size());
    return status;
  }
  const int jobs = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(opt.jobs), std::max<std::size_t>(todo, 1)));
  const auto argv_of = [&](int w) {
    std::vector<std::string> args{opt.executable, "run", opt.config_path, "--out", dir.string(),
                                  "--worker", std::to_string(w) + "/" + std::to_string(jobs),
                                  "--shard", std::to_string(opt.shard.index) + "/" + std::to_string(opt.shard.count)};
    if (opt.smoke) args.emplace_back("--smoke");
    for (const auto& s : opt.sets) args.insert(args.end(), {"--set", s});
    for (const auto& f : opt.filters) args.insert(args.end(), {"--filter", f});
    return args;
  };
  const auto run_in_progress = [&](int w) {
    std::ifstream in(marker_of(dir, w));
    std::string id;
    std::getline(in, id);
    return id;
  };
  std::set<std::string> crashed;
  const auto on_crash = [&](const WorkerCrash& c) {
    for (std::size_t i : plan.selected) {
      if (plan.space->run_id(i) != c.run_id) continue;
      const RunPoint p = plan.space->point(i);
      const MetricRow m = crashed_row("the worker process was " + c.reason + " during this run");
      const auto keys = key_fields(plan, p, m);
      commit_run(dir, plan.layout, keys, runs_row(plan, keys, m), RunTables{});
      crashed.insert(p.run_id);  // its table rows, if it committed some, go at the end
      std::cerr << "fairshape: run " << p.run_id << " crashed: the worker was " << c.reason << "\n";
    }
    fs::remove(marker_of(dir, c.worker));
  };
  const SupervisorResult r = supervise_workers(jobs, argv_of, run_in_progress, on_crash);
  folder.roll_back_orphan_rows(plan.layout, crashed);
  remove_run_markers(folder, dir);
  const int status = r.interrupted_by ? 128 + r.interrupted_by : r.status;
  journal.close(status, folder.finished_runs(plan.layout).size());
  if (r.interrupted_by)
    std::cerr << "fairshape: interrupted by signal " << r.interrupted_by << "; continue with --resume --out "
              << dir.string() << "\n";
  return status;
}

}  // namespace

Slice Slice::parse(const std::string& text, const std::string& option) {
  Slice s;
  const auto slash = text.find('/');
  std::size_t end_i = 0, end_n = 0;
  try {
    if (slash == std::string::npos) throw std::invalid_argument("");
    s.index = std::stoi(text.substr(0, slash), &end_i);
    s.count = std::stoi(text.substr(slash + 1), &end_n);
  } catch (const std::exception&) {
    throw InvalidConfig(option + " '" + text + "': expected i/n, e.g. 0/4");
  }
  if (end_i != slash || end_n != text.size() - slash - 1)
    throw InvalidConfig(option + " '" + text + "': expected i/n, e.g. 0/4");
  if (s.count < 1 || s.index < 0 || s.index >= s.count)
    throw InvalidConfig(option + " '" + text + "': need 0 <= i < n");
  return s;
}

int run_sweep(const SweepOptions& opt) { return opt.is_worker ? run_worker(opt) : supervise(opt); }

SweepCheck check_sweep(const SweepOptions& opt) {
  const Plan plan = make_plan(opt, true);
  return {plan.name, plan.kind->name(), plan.space->size(), plan.selected.size()};
}

}  // namespace fairshape
