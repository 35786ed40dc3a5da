// Curve experiments (configs/sauvage): a polyline, a list of edits each run through the
// editing loop of Sauvage, Hahmann and Bonneau (§4.1), and the length-constrained
// optimization that ends every loop. A config is a curve run when it has `input.curve`.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "fairshape/curve_design/curve_session.h"
#include "fairshape/experiment/run_outputs.h"
#include "fairshape/experiment/vtk_policy.h"
#include "fairshape/experiment/run_basics.h"

namespace fairshape {

struct CurveRunSpec : RunBasics {
  std::string curve_path, solver_type;
  int levels = 0;
  Polyline curve;
  std::vector<CurveEdit> edits;
  //! The session's settings: the `editing:` block (the same for every edit; editing.partial_edit:
  //! accept lets an edit the explicit step or the constraints could not honour end converged,
  //! its message saying what happened) and the `optimization:` block's objective and solver.
  CurveEditSettings settings;
  VtkPolicy vtk = VtkPolicy::Final;
  bool final_curve = true;
  //! runs.csv's wrinkle_amplitude, wrinkle_wavelength(_segments) (wrinkle_scale.h): an FFT of the
  //! whole curve per run; false leaves them empty (a designer's drag need not pay for them).
  bool wrinkle_scale = true;

  //! Reads and checks everything, the curve file included (its point count against the
  //! hierarchy, every edit's levels and control points). \throw InvalidConfig naming the key.
  //! Every key a run of this kind reads, with its default and doc (document_keys).
  static std::vector<OptionDoc> keys();
  static CurveRunSpec from_config(const YAML::Node& run_config, const std::vector<std::string>& search_dirs);
};

//! A session's settings from the `editing:` and `optimization:` blocks of `root` (a curve config,
//! or Python's CurveSession keywords), read and checked against `curve` (`curve_name` in
//! messages) with basics.implementation; the options of solvers not chosen are noted in
//! basics.unused_keys, the chosen solver's name in `solver_type`. \throw InvalidConfig naming the key.
CurveEditSettings read_curve_settings(Config& root, const Polyline& curve, const std::string& curve_name, RunBasics& basics,
                                      std::string& solver_type);
//! One `edits:` entry: the whole move and the editing loops it is split into (drag_steps in
//! editing_loop.h makes them).
struct CurveEditEntry {
  CurveEdit whole;
  int drag_steps = 1;
};
//! An `edits:` entry (a config's, or Python's CurveSession.edit / drag_step keywords). `on`: the
//! run whose hierarchy its level and control points must lie on, checked here with the keys'
//! names (nullptr: the session checks them when the edit is made).
CurveEditEntry read_curve_edit(Config& entry, const CurveRunSpec* on);

bool is_curve_config(const YAML::Node& run_config);

const std::vector<std::string>& curve_metric_columns();  // runs.csv
const std::vector<std::string>& curve_step_columns();    // steps.csv: one row per edit and stage
const std::vector<std::string>& curve_iteration_columns();  // iterations.csv: one row per solve of each edit

//! Runs every edit in order through a CurveSession (each on the previous result; its settings
//! are moved out of `spec`), writes the stages' curves (VTK polylines and OBJ under curves/),
//! steps.csv rows and final.obj. Never throws for problems of the input or the numerics: they
//! become the row's termination and message.
MetricRow execute_curve_run(CurveRunSpec& spec, const RunOutputs& out);

}  // namespace fairshape
