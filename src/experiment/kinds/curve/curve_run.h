// Curve experiments (configs/sauvage): a polyline, a list of edits each run through the
// editing loop of Sauvage, Hahmann and Bonneau (§4.1), and the length-constrained
// optimization that ends every loop. A config is a curve run when it has `input.curve`.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "fairshape/curve_design/editing_loop.h"
#include "fairshape/experiment/run_outputs.h"
#include "fairshape/experiment/vtk_policy.h"
#include "fairshape/experiment/run_basics.h"

namespace fairshape {

struct CurveRunSpec : RunBasics {
  std::string curve_path, solver_type;
  int levels = 0;
  Polyline curve;
  std::vector<CurveEdit> edits;
  EditingOptions editing;  // `editing:` block, the same for every edit
  //! editing.partial_edit: accept — an edit the explicit step or the constraints could not
  //! honour (handles pulled back or undone, attracting-curve lengths left wrong) still ends
  //! converged, its message saying what happened; fail (default) — it ends edit_undone or
  //! constraints_unmet.
  bool accept_partial_edit = false;
  double beta = 0.5;
  std::unique_ptr<CurveEnergy> smoothness;
  std::vector<std::unique_ptr<CurveConstraintKind>> constraints;
  std::unique_ptr<LengthSolver> solver;
  VtkPolicy vtk = VtkPolicy::Final;
  bool final_curve = true;
  //! runs.csv's wrinkle_amplitude, wrinkle_wavelength(_segments) (wrinkle_scale.h): an FFT of the
  //! whole curve per run; false leaves them empty (a designer's drag need not pay for them).
  bool wrinkle_scale = true;

  CurveObjective objective() const;
  //! Reads and checks everything, the curve file included (its point count against the
  //! hierarchy, every edit's levels and control points). \throw InvalidConfig naming the key.
  //! Every key a run of this kind reads, with its default and doc (document_keys).
  static std::vector<OptionDoc> keys();
  static CurveRunSpec from_config(const YAML::Node& run_config, const std::vector<std::string>& search_dirs);
};

bool is_curve_config(const YAML::Node& run_config);

const std::vector<std::string>& curve_metric_columns();  // runs.csv
const std::vector<std::string>& curve_step_columns();    // steps.csv: one row per edit and stage
const std::vector<std::string>& curve_iteration_columns();  // iterations.csv: one row per solve of each edit

//! Runs every edit in order (each on the previous result), writes the stages' curves (VTK
//! polylines and OBJ under curves/), steps.csv rows and final.obj. Never throws for problems
//! of the input or the numerics: they become the row's termination and message.
MetricRow execute_curve_run(CurveRunSpec& spec, const RunOutputs& out);

}  // namespace fairshape
