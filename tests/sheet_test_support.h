// Running a sheet config in a test (the session and free-curve tests).
#pragma once

#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "fairshape/experiment/kinds/sheet/sheet_run.h"
#include "fairshape/experiment/run_outputs.h"
#include "test_support.h"

namespace fairshape::test {

//! Runs `cfg` in a fresh scratch folder named `folder` with run id `id`; returns steps.csv's
//! rows (step, sheet, dofs, levels, constraint_rows, dropped_rows, constraint_residual,
//! max_constraint_error, energy, ...) and sets `row` to runs.csv's.
inline std::vector<std::vector<std::string>> run_sheet_steps(const YAML::Node& cfg, const std::string& folder, const std::string& id,
                                                             MetricRow& row) {
  const auto dir = scratch_dir(folder);
  create_run_folders(dir.string());
  SheetRunSpec spec = SheetRunSpec::from_config(cfg);
  RunTables tables;
  row = execute_sheet_run(spec, RunOutputs{dir.string(), id, true, &tables});
  return tables.rows().at("steps");
}

}  // namespace fairshape::test
