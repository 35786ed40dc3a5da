// Running a sheet config in a test (the session and free-curve tests).
#pragma once

#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "fairshape/bspline/sheet_geometry.h"
#include "fairshape/bspline/variational_sheet.h"
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

//! The four push-pins of the sheet configs' tests (design units, a 2 × 2 sheet held where it
//! is): `constraints:` items, to be followed by the test's own.
inline const char* const kCornerPinsYaml = R"(
  - {type: point, uv: [0.125, 0.125], by: [0, 0, 0]}
  - {type: point, uv: [1.875, 0.125], by: [0, 0, 0]}
  - {type: point, uv: [0.125, 1.875], by: [0, 0, 0]}
  - {type: point, uv: [1.875, 1.875], by: [0, 0, 0]})";

//! An 8 × 8-span bicubic sheet of size 2 × 2 in the z = 0 plane (a span is 0.25 design units).
inline bspline::VariationalSheet flat_sheet() {
  const bspline::SheetShape shape{8, 8, 3, false, {0.25, 0.25}};
  bspline::SheetPlacement placement;
  placement.size_u = placement.size_v = 2;
  return bspline::VariationalSheet(shape, bspline::initial_coefficients(placement, bspline::HierarchicalSurface(shape)));
}

//! Point constraints at (u, v) ∈ {0.5, 7.5}² (base spans), holding the sheet where it is there.
inline std::vector<bspline::SheetConstraint> corner_pins(const bspline::VariationalSheet& sheet) {
  std::vector<bspline::SheetConstraint> out;
  for (double u : {0.5, 7.5})
    for (double v : {0.5, 7.5}) {
      bspline::SheetConstraint c;
      c.u = u, c.v = v;
      c.target = sheet.surface().position(sheet.coefficients(), u, v);
      out.push_back(c);
    }
  return out;
}

}  // namespace fairshape::test
