// A kind of experiment run (a Catmull-Clark surface edit, a B-spline sheet design, a curve
// edit, a feature-curve run): what the harness needs to know of it and nothing more. The
// harness (sweep_runner) owns everything around a run — the output folder, its tables,
// resume, workers, progress, exit status — and a kind owns its configs and its computation.
// A new kind is one folder under kinds/ and one line in register_run_kinds().
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "fairshape/core/config.h"
#include "fairshape/experiment/repeats.h"
#include "fairshape/experiment/run_outputs.h"

namespace fairshape {

//! What validating one run's config tells the harness.
struct ValidatedRun {
  std::string name;                      // the experiment's name (results/<name>/)
  std::vector<std::string> input_files;  // resolved paths of every file the run will read
};

class RunKind {
 public:
  virtual ~RunKind() = default;
  virtual std::string name() const = 0;
  //! The top-level key that makes a config this kind's (e.g. `sheets`), for error messages.
  virtual std::string marker() const = 0;
  virtual bool owns(const YAML::Node& run_config) const = 0;
  //! Parses and checks everything that needs only the config and its input files.
  //! \throw InvalidConfig naming the key.
  //! Checks needing the input's geometry (a constraint's vertex, a curve on the surface) are
  //! made here too, on meshes a kind may keep until validation_done().
  virtual ValidatedRun validate(const YAML::Node& run_config, const std::vector<std::string>& search_dirs) = 0;
  //! Every point is validated: what validation kept (hierarchies) can go.
  virtual void validation_done() {}
  //! runs.csv's columns after run_id and the swept parameters, termination and message included.
  virtual const std::vector<std::string>& metric_columns() const = 0;
  //! The metric columns that vary from one execution to the next (timings, memory): over a
  //! run's `repeat` executions the harness reports their median (experiment/repeats.h).
  virtual std::vector<std::string> measured_columns() const { return measured_by_name(metric_columns()); }
  //! The other tables its runs fill through RunOutputs::add_row.
  virtual std::vector<TableSchema> tables() const = 0;
  //! Metric columns the harness also puts on every row of every table, to key plots by
  //! solver rather than by hash (e.g. implementation, solver.type).
  virtual std::vector<std::string> identity_columns() const { return {"implementation", "solver.type"}; }
  //! Every key its configs may have, with default and doc (`fairshape list --keys`, `schema`).
  virtual std::vector<OptionDoc> keys() const = 0;
  //! Runs one validated config once (the harness repeats it for `repeat:`). Problems of the input or the numerics become the row's
  //! termination and message; anything else thrown is turned into a `crashed` row by the harness.
  virtual MetricRow execute(const YAML::Node& run_config, const std::vector<std::string>& search_dirs,
                            const RunOutputs& out) = 0;
};

//! A fresh instance of every kind (kinds may keep caches across the runs of one process).
std::vector<std::unique_ptr<RunKind>> make_run_kinds();
//! The kind owning a config. \throw InvalidConfig when none or several do, naming their markers.
RunKind& kind_of(const YAML::Node& run_config, const std::vector<std::unique_ptr<RunKind>>& kinds);

}  // namespace fairshape
