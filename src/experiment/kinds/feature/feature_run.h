// Feature-curve experiments (configs/khodakovsky-schroder): a Loop hierarchy of a mesh, feature
// curves drawn on its levels, an optional coarse edit of the base surface (Figure 15), and an
// adaptive mesh of the result. A config is a feature run when it has `features:`.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "fairshape/experiment/run_outputs.h"
#include "fairshape/experiment/run_basics.h"
#include "fairshape/experiment/kinds/sheet/sheet_run.h"
#include "fairshape/feature/base_edit.h"
#include "fairshape/feature/curve_placement.h"
#include "fairshape/feature/feature_drawing.h"
#include "fairshape/feature/feature_curve.h"
#include "fairshape/feature/feature_session.h"
#include "fairshape/feature/featured_surface.h"
#include "fairshape/subdivision/scheme.h"

namespace fairshape {

struct SurfaceEditSpec;  // experiment/kinds/surface_edit/surface_edit_spec.h

//! A feature's parameters from a design step on (`changes: [{step, height, radius, ...}]`).
struct FeatureChange {
  int step = 1;
  feature::FeatureParams params;
};

//! A feature's profile parameters from its config block (or `feature_defaults`), each key
//! defaulting to `defaults`; out-of-range values are errors naming the key.
feature::FeatureParams read_feature_params(Config& c, const feature::FeatureParams& defaults);

//! A feature of the config: how it is drawn (feature/feature_drawing.h: curve, points or tool,
//! max_distance, key) and its schedule over the design steps.
struct FeatureSpec : feature::FeatureDrawing {
  bool after_edit = false;           // drawn on the surface the `edit` made (else before it, carried by it)
  // Over the design steps (feature_steps.h): added at `step`, removed from `until` (−1: never),
  // moved as a whole by `moves` (world points only; they add up), re-parameterized by `changes`.
  int step = 0, until = -1;
  std::vector<PointMove> moves;
  std::vector<FeatureChange> changes;
  int id = -1;                       // its id in the run's FeatureSession while it is there
};

//! One `features:` entry ("features[3]" is `where`), its parameters defaulting to `defaults`.
//! \throw InvalidConfig naming the key.
FeatureSpec read_feature_entry(Config& c, const std::string& where, const std::vector<std::string>& dirs, int levels,
                               const feature::FeatureParams& defaults, bool has_edit);

struct BaseEditSpec {
  bool enabled = false;
  feature::BaseEdit edit;
};

struct FeatureRunSpec : RunBasics {
  std::string mesh_path;             // a triangle mesh, or a saved Loop hierarchy (.vtm, with its details)
  LoopWeights loop_weights = LoopWeights::Loop;
  int levels = 3;
  int remesh_base_faces = 0;         // > 0: the input remeshed into a Loop hierarchy with details
  //! The hierarchy and the `edit` as the surface-edit kind reads them (Boier-Martin et al.'s
  //! detail-preserving editor, on the surface without features): set when the input is
  //! remeshed or saved, or an edit is given.
  std::shared_ptr<SurfaceEditSpec> editor;
  bool has_edit = false;
  feature::FeatureParams feature_defaults;  // `feature_defaults`, which every feature starts from
  std::vector<FeatureSpec> features;
  BaseEditSpec base_edit;
  bool adaptive = true;
  //! adaptive.evaluation: uniform (thinned from the uniform hierarchy by the smallest threshold)
  //! or sparse (feature/adaptive_evaluation.h: computed only where refined, each feature's own
  //! threshold, `adaptive.surface_angle_deg` elsewhere).
  bool adaptive_sparse = false;
  double adaptive_surface_angle_deg = 0;
  //! sparse: the largest level (in faces) a placement tool may have computed whole
  //! (`adaptive.placement_max_faces`; geodesic, section and polyline need their whole level).
  int adaptive_placement_max_faces = 300000;
  feature::ProfileTarget profile_target = feature::ProfileTarget::Limit;  // `profile_on`
  //! step_evaluation: region (default; a design step recomputes only what its features reach)
  //! or whole (every step evaluates the whole hierarchy).
  bool region_steps = true;
  bool vtk = true;
  bool vtk_every_step = false;       // output.vtk: all — vtk/<run>_step<k>.vtp after every design step
  //! \throw InvalidConfig naming the key.
  //! Every key a run of this kind reads, with its default and doc (document_keys).
  static std::vector<OptionDoc> keys();
  static FeatureRunSpec from_config(const YAML::Node& run_config, const std::vector<std::string>& search_dirs);
};

bool is_feature_config(const YAML::Node& run_config);
const std::vector<std::string>& feature_metric_columns();
//! features.csv beside runs.csv: one row per feature and run, the achieved profile
//! (feature/profile_measure.h) on the finest level and at the limit.
const TableSchema& feature_profile_table();

//! The run's Loop hierarchy of input.mesh, without features. \throw Error for the input.
MultiresSurface feature_hierarchy(const FeatureRunSpec& spec);
//! The session options a run's keys give (implementation, profile_on, step_evaluation).
FeatureSessionOptions feature_session_options(const FeatureRunSpec& spec);
//! A session on `original` with the run's first features drawn before the edit placed on it
//! (world points projected, faces and widths checked; ids in spec.features[k].id) and the base
//! edit applied; not yet evaluated. \throw InvalidInput naming the feature.
std::unique_ptr<FeatureSession> placed_features(FeatureRunSpec& spec, MultiresSurface original);
//! Places the first step's features drawn after the edit on the session's current original (the
//! edited one). \throw InvalidInput naming the feature.
void place_features_after_edit(FeatureRunSpec& spec, FeatureSession& session);

//! A run's session prepared as the run prepares it: the hierarchy, the first step's features
//! drawn before the edit, the edit (the radial bump, or the detail-preserving `edit` block), those
//! drawn after it; not yet evaluated (its first step does that). `edit`: the detail-preserving
//! edit's outcome, when there is one; when it failed the features drawn after it are not placed.
struct OpenedFeatureSession {
  std::unique_ptr<FeatureSession> session;
  std::optional<SolveSummary> edit;
  double edit_s = 0;
  double diagonal = 0;  // of the finest level before any edit (the run's displacement threshold)
};
//! \throw Error for the input (as feature_hierarchy and placed_features).
OpenedFeatureSession open_feature_session(FeatureRunSpec& spec);

//! `step_evaluation`'s values: region (true), whole (false).
const NameTable<bool>& step_evaluation_names();

//! Writes final.obj (finest level), vtk/<run>.vtp (point arrays displacement, displacement_norm,
//! limit_position, limit_normal), adaptive/<run>.obj, curves/<run>_<feature>.obj, features.csv,
//! attachments.csv and (with VTK output) levels/<run>_level<k>.vtp and limit/<run>.vtp
//! (feature_exports.h); never throws for problems of the input. With adaptive.evaluation: sparse
//! the uniform hierarchy is never built (sparse_run.h): final.obj is the adaptive mesh.
MetricRow execute_feature_run(FeatureRunSpec& spec, const RunOutputs& out);

}  // namespace fairshape
