#include "fairshape/experiment/kinds/feature/feature_run.h"

#include "fairshape/experiment/kinds/feature/feature_exports.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <utility>
#include <limits>
#include <map>
#include <sstream>

#include "fairshape/core/summary.h"
#include "fairshape/core/config.h"
#include "fairshape/core/timer.h"
#include "fairshape/experiment/kinds/feature/curve_placement_config.h"
#include "fairshape/experiment/kinds/feature/feature_exports.h"
#include "fairshape/experiment/components.h"
#include "fairshape/experiment/kinds/feature/feature_steps.h"
#include "fairshape/experiment/kinds/feature/feature_width_check.h"
#include "fairshape/experiment/kinds/feature/sparse_run.h"
#include "fairshape/core/memory.h"
#include "fairshape/experiment/kinds/sheet/constraint_schedule.h"
#include "fairshape/experiment/kinds/surface_edit/edited_hierarchy.h"
#include "fairshape/experiment/kinds/surface_edit/run_one.h"
#include "fairshape/experiment/metric_format.h"
#include "fairshape/feature/adaptive_mesh.h"
#include "fairshape/feature/featured_surface.h"
#include "fairshape/feature/profile_measure.h"
#include "fairshape/io/constraint_overlay.h"
#include "fairshape/io/contour_lines.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/experiment/vtk_policy.h"
#include "fairshape/io/vtk_io.h"
#include "fairshape/mesh/polyline.h"

namespace fairshape {
namespace fs = std::filesystem;

namespace {


// The surface-edit keys an `edit` block passes through (experiment/kinds/surface_edit).
const std::vector<std::string> kEditKeys{"energy", "constraints", "problem", "solver"};

// The hierarchy and the edit through the surface-edit kind's reader, when the input is remeshed
// or saved or an `edit` is given: the same keys, the same checks, the same hierarchy (its
// remesher, its saved files). Its messages name the keys inside `edit`.
void read_editor(Config& root, const std::vector<std::string>& dirs, FeatureRunSpec& s) {
  const YAML::Node& config = root.node();
  const bool saved = std::filesystem::path(s.mesh_path).extension() == ".vtm";
  s.has_edit = root.has("edit");
  Config ec = root.child("edit", "a detail-preserving edit (Boier-Martin et al.) of the surface without features, in the "
                                 "surface-edit keys {energy, constraints, problem, solver}; features ride on it");
  for (const std::string& k : kEditKeys) (void)ec.get<YAML::Node>(k, YAML::Node(), "as in a surface-edit config");
  ec.check_no_unknown_keys();
  if (!s.has_edit && !saved && s.remesh_base_faces == 0) return;
  YAML::Node edit_config;
  edit_config["name"] = s.name;
  edit_config["implementation"] = std::string(to_string(s.implementation));
  YAML::Node input = YAML::Clone(config["input"]);
  if (!saved) input["representation"] = "loop";
  edit_config["input"] = input;
  if (s.has_edit)
    for (const std::string& k : kEditKeys)
      if (config["edit"][k]) edit_config[k] = YAML::Clone(config["edit"][k]);
  // Without an edit the reader builds only the hierarchy: an energy it requires, never used.
  if (!s.has_edit) edit_config["energy"] = YAML::Load("[{type: detail_preserving}]");
  if (!edit_config["constraints"]) edit_config["constraints"] = YAML::Load("[]");
  edit_config["output"] = YAML::Load("{vtk: none, iterations: false, final_mesh: false, reference_solution: false}");
  try {
    s.editor = std::make_shared<SurfaceEditSpec>(SurfaceEditSpec::from_config(edit_config, components(), dirs));
  } catch (const InvalidConfig& e) {
    const std::string what = e.what();
    const bool inside = std::any_of(kEditKeys.begin(), kEditKeys.end(), [&](const std::string& k) { return what.rfind(k, 0) == 0; });
    throw InvalidConfig(inside ? "edit." + what : what);
  }
  if (s.editor->representation != Representation::Loop)
    throw InvalidConfig("input.mesh: " + s.mesh_path + " is not a Loop hierarchy: features need triangles (Loop)");
  s.levels = s.editor->levels;
}

}  // namespace

feature::FeatureParams read_feature_params(Config& c, const feature::FeatureParams& d) {
  feature::FeatureParams p;
  p.radius = c.get_number("radius", d.radius, 1e-12, 1e12, "neighbourhood size r (left of the curve), world units");
  p.left_right_ratio = c.get_number("left_right_ratio", d.left_right_ratio, 1e-3, 1e3, "r_left / r_right (§2.7)");
  p.height = c.get_number("height", d.height, -1e12, 1e12, "profile height at the curve (negative: groove)");
  p.crease = c.get_number("crease", d.crease, -1e3, 1e3, "profile slope at the curve (0: smooth)");
  p.end_height_ratio = c.get_number("end_height_ratio", d.end_height_ratio, 0, 1e3, "height at the end / at the start");
  p.flatness_angle_deg = c.get_number("flatness_angle_deg", d.flatness_angle_deg, 1e-3, 89.9,
                                      "adaptive refinement threshold in degrees (§2.5)");
  p.max_turn_deg = c.get_number("max_turn_deg", d.max_turn_deg, 1, 179,
                                "largest turn of the surface normal within the radius before the feature is refused");
  p.quadratic = c.get<bool>("quadratic", d.quadratic, "frames on the quadratic spline of the polygon (§2.4)");
  p.quadratic_samples = c.get_int("quadratic_samples", d.quadratic_samples, 1, 256, "straight pieces per quadratic span");
  // Visible profile: how closely the finest level and the limit must show it.
  p.profile_tolerance = c.get_number("profile_tolerance", d.profile_tolerance, 1e-6, 1,
                                     "largest height / profile error as a fraction of |height| (finest level and limit)");
  p.width_tolerance = c.get_number("width_tolerance", d.width_tolerance, 1e-6, 1,
                                   "largest width error as a fraction of the radius (finest level and limit)");
  return p;
}

const NameTable<bool>& step_evaluation_names() {
  static const NameTable<bool> names{{true, "region"}, {false, "whole"}};
  return names;
}

FeatureSpec read_feature_entry(Config& c, const std::string& where, const std::vector<std::string>& dirs, int levels,
                               const feature::FeatureParams& defaults, bool has_edit) {
  FeatureSpec f;
  f.curve.name = c.get<std::string>("name", where, "name in outputs and messages");
  f.curve.level = c.get_int("level", 0, 0, levels, "the hierarchy level the curve is drawn on");
  f.curve.params = read_feature_params(c, defaults);
  f.max_distance = c.get_number("max_distance", 0.02, 0, 1, "× bounding-box diagonal: farther points leave the surface");
  f.after_edit = c.get<bool>("after_edit", false, "drawn on the surface the edit made (default: before it, carried by it)");
  read_schedule(c, f.step, f.until);
  f.moves = read_moves(c, f.step);
  if (!f.moves.empty() && !c.has("points") && !c.documenting())
    throw InvalidConfig(c.key_path("moves") + ": only a feature given by world `points` is moved (its points are translated "
                        "and placed again)");
  for (Config ch : c.child_list("changes", "its parameters from a later step on: [{step, height, radius, crease, ...}]")) {
    FeatureChange change;
    change.step = ch.get_int("step", 1, 1, 1000, "design step from which the parameters apply");
    change.params = read_feature_params(ch, f.changes.empty() ? f.curve.params : f.changes.back().params);
    ch.check_no_unknown_keys();
    if (change.step <= f.step || (!f.changes.empty() && change.step <= f.changes.back().step))
      throw InvalidConfig(ch.key_path("step") + ": " + std::to_string(change.step) +
                          " must come after the feature's step and its earlier changes");
    try {
      change.params.validate(ch.path());
    } catch (const InvalidInput& e) {
      throw InvalidConfig(e.what());
    }
    f.changes.push_back(change);
  }
  if (f.after_edit && !has_edit) throw InvalidConfig(c.key_path("after_edit") + ": there is no edit (give an `edit` block)");
  f.key = where;
  read_curve_source(c, where, dirs, f);
  try {
    f.curve.params.validate(where);
  } catch (const InvalidInput& e) {
    throw InvalidConfig(e.what());
  }
  c.check_no_unknown_keys();
  return f;
}

bool is_feature_config(const YAML::Node& c) { return c.IsMap() && c["features"].IsDefined(); }

// Every key of the run read from `root` (parse_config: unknown keys reported together).
static FeatureRunSpec read_feature_run(const std::vector<std::string>& dirs, Config& root) {
  FeatureRunSpec s;
  static_cast<RunBasics&>(s) = read_run_basics(root);
  Config in = root.child("input", "the base mesh: {mesh, levels, weights, remesh_base_faces}");
  s.mesh_path = read_input_path(in, "mesh", "a triangle mesh (OFF/OBJ/PLY), or a saved Loop hierarchy (.vtm)", dirs);
  s.levels = in.get_int("levels", 3, 0, 8, "uniform Loop subdivision steps");
  s.loop_weights = in.get_enum("weights", LoopWeights::Loop, loop_weight_names(), "Loop vertex weights (warren: 3/8k, the paper's)");
  s.remesh_base_faces = in.get_int("remesh_base_faces", 0, 0, 10000000,
                                   "remesh the input into a Loop hierarchy with details from about this many base faces (0: the "
                                   "input mesh is the base)");
  in.check_no_unknown_keys();
  read_editor(root, dirs, s);
  Config dc = root.child("feature_defaults", "parameters every feature starts from (sweepable: feature_defaults.height)");
  const feature::FeatureParams defaults = read_feature_params(dc, feature::FeatureParams{});
  dc.check_no_unknown_keys();
  s.feature_defaults = defaults;
  int k = 0;
  for (Config c : root.child_list("features", "feature curves [{name, level, points | surface_points, ...}]")) {
    std::ostringstream where;
    where << "features[" << k++ << "]";
    s.features.push_back(read_feature_entry(c, where.str(), dirs, s.levels, defaults, s.has_edit));
  }
  if (s.features.empty()) throw InvalidConfig("features: at least one feature curve");
  std::vector<std::pair<std::string, std::string>> names;
  for (const FeatureSpec& f : s.features) names.emplace_back(f.key + ".name", f.curve.name);
  check_distinct_file_names(names);
  Config ec = root.child("base_edit", "a coarse edit of the base surface (Figure 15): {enabled, nearest, offset, radius}");
  s.base_edit.enabled = ec.get<bool>("enabled", ec.has("offset"), "apply the edit");
  s.base_edit.edit.nearest = read_vec3(ec, "nearest", Vec3::Zero(), "the edit's centre: the base vertex nearest to this point");
  s.base_edit.edit.offset = read_vec3(ec, "offset", Vec3::Zero(), "displacement of the centre");
  s.base_edit.edit.radius = ec.get_number("radius", 0.3, 1e-6, 10, "falloff radius × bounding-box diagonal");
  ec.check_no_unknown_keys();
  if (s.base_edit.enabled && s.has_edit)
    throw InvalidConfig("base_edit: give the radial bump or a detail-preserving `edit`, not both");
  s.profile_target = root.get_enum("profile_on", feature::ProfileTarget::Limit, feature::profile_target_names(),
                                   "where the profile is exact: limit (the limit surface at the finest vertices), "
                                   "finest (the finest control points) or drawn_level (the paper: the drawn level's control points)");
  const bool step_key = root.has("step_evaluation");
  s.region_steps = root.get_enum("step_evaluation", true, step_evaluation_names(),
                                 "design steps: region (recompute what the step's features reach) or whole (the whole "
                                 "hierarchy every step)");
  Config ac = root.child("adaptive", "adaptive output mesh (§2.5): {enabled, evaluation, surface_angle_deg}");
  s.adaptive = ac.get<bool>("enabled", true, "write adaptive/<run>.obj refined by the features' flatness thresholds");
  static const NameTable<bool> evaluations{{false, "uniform"}, {true, "sparse"}};
  s.adaptive_sparse = ac.get_enum("evaluation", false, evaluations,
                                  "uniform (thinned from the uniform hierarchy by the smallest flatness_angle_deg) or "
                                  "sparse (computed only where a feature or the flatness test refines, each feature's "
                                  "own threshold)");
  s.adaptive_surface_angle_deg =
      ac.get_number("surface_angle_deg", 0.0, 0.0, 89.9,
                    "sparse: flatness threshold of the surface away from the features (0: not refined there)");
  const bool placement_key = ac.has("placement_max_faces");
  s.adaptive_placement_max_faces =
      ac.get_int("placement_max_faces", s.adaptive_placement_max_faces, 1, 1 << 30,
                 "sparse: the most faces a level may have for a placement tool (geodesic, section, polyline) to "
                 "compute it whole and place a curve there");
  ac.check_no_unknown_keys();
  if (!s.adaptive_sparse && placement_key)
    throw InvalidConfig("adaptive.placement_max_faces: only with adaptive.evaluation: sparse (a uniform run has every level whole)");
  if (s.adaptive_sparse) {
    // The sparse levels are the plain mesh's Loop levels: a hierarchy's details or an edit would
    // have to be refined wherever they are nonzero (not done).
    if (s.editor) throw InvalidConfig("adaptive.evaluation: sparse needs a plain triangle mesh: no remesh_base_faces, "
                                      "saved hierarchy or edit (their details are not evaluated sparsely)");
    if (s.base_edit.enabled) throw InvalidConfig("adaptive.evaluation: sparse cannot be combined with base_edit");
  } else if (ac.has("surface_angle_deg")) {
    throw InvalidConfig("adaptive.surface_angle_deg: only with adaptive.evaluation: sparse");
  }
  Config oc = root.child("output", "what each run writes");
  const VtkPolicy vtk = read_vtk_policy(oc, "vtk/<run>_step<k>.vtp after every design step as well");
  s.vtk = vtk != VtkPolicy::None;
  s.vtk_every_step = vtk == VtkPolicy::All;
  oc.check_no_unknown_keys();
  root.check_no_unknown_keys();
  if (s.adaptive_sparse) check_sparse_run(s);
  if (step_key && s.adaptive_sparse)
    throw InvalidConfig("step_evaluation: a sparse run has no design steps (valid with adaptive.evaluation: uniform)");
  if (step_key && feature_step_count(s) == 1)
    throw InvalidConfig("step_evaluation: the features schedule no design step after the first (give a feature "
                        "step, until, moves or changes), so nothing is re-evaluated");
  return s;
}

std::vector<OptionDoc> FeatureRunSpec::keys() {
  return document_keys([](Config& root) { (void)read_feature_run({}, root); });
}

FeatureRunSpec FeatureRunSpec::from_config(const YAML::Node& run_config, const std::vector<std::string>& dirs) {
  return parse_config(run_config, [&](Config& root) { return read_feature_run(dirs, root); });
}

const std::vector<std::string>& feature_metric_columns() {
  static const std::vector<std::string> cols{"features", "levels", "n_fine", "segments", "edit_s", "apply_s", "vertices_moved",
                                             "max_displacement", "triangles_uniform", "triangles_adaptive",
                                             "adaptive_evaluation", "adaptive_faces_computed", "peak_rss_mb",
                                             "profile_on", "features_within_tolerance", "worst_profile_error_fine",
                                             "worst_profile_error_limit", "worst_height_error", "worst_width_error", "flipped_faces", "time_s",
                                             "unused_keys", "termination", "message"};
  return cols;
}

const TableSchema& feature_profile_table() {
  static const TableSchema t{"features",
                             {"feature", "level", "height", "radius_left", "radius_right",
                              "height_min_fine", "height_max_fine", "width_left_fine", "width_right_fine", "height_error_fine",
                              "width_error_fine", "profile_error_fine", "height_min_limit", "height_max_limit",
                              "width_left_limit", "width_right_limit", "height_error_limit", "width_error_limit",
                              "profile_error_limit", "within_tolerance", "miss", "gated_on"}};
  return t;
}

namespace {

double bounding_diagonal(const SurfaceMesh& m) {
  return (m.positions().colwise().maxCoeff() - m.positions().colwise().minCoeff()).norm();
}

}  // namespace

MultiresSurface feature_hierarchy(const FeatureRunSpec& spec) {
  if (spec.editor) {  // remeshed, saved or edited: the surface-edit kind's hierarchy
    RunCache cache;  // one run's: its hierarchy is part of the run's time
    return cache.hierarchy(*spec.editor);
  }
  SubdivisionOptions opt;
  opt.scheme = SchemeType::Loop;
  opt.weights = spec.loop_weights;
  return MultiresSurface(read_mesh(spec.mesh_path), opt, spec.levels, spec.implementation);
}

FeatureSessionOptions feature_session_options(const FeatureRunSpec& spec) {
  FeatureSessionOptions o;
  o.backend = spec.implementation;
  o.profile_target = spec.profile_target;
  o.region_steps = spec.region_steps;
  return o;
}

namespace {
// Adds the features of the first step drawn before or after the edit, placed on the session's
// current original; the widths of their later `changes` checked too.
void place_features(FeatureRunSpec& spec, FeatureSession& session, bool after_edit) {
  for (FeatureSpec& f : spec.features) {
    if (f.after_edit != after_edit || f.step > 0) continue;  // later steps add theirs (feature_steps.h)
    f.id = session.stage_add(f);
    f.curve = session.features().at(f.id);
    check_feature_width(f, session.original().mesh(0), spec.levels);
  }
}
}  // namespace

std::unique_ptr<FeatureSession> placed_features(FeatureRunSpec& spec, MultiresSurface original) {
  auto session = std::make_unique<FeatureSession>(std::move(original), feature_session_options(spec));
  const double diag = bounding_diagonal(session->original().mesh(spec.levels));
  place_features(spec, *session, false);
  // The curves are attached to the unedited levels (face, barycentric coordinates), so a base
  // edit carries them.
  if (spec.base_edit.enabled) {
    MultiresSurface& edited = session->edit_original();
    edited.set_base_positions(feature::bumped_positions(edited.mesh(0), spec.base_edit.edit, diag));
    edited.synthesize(DetailSpace::Local);
  }
  return session;
}

void place_features_after_edit(FeatureRunSpec& spec, FeatureSession& session) { place_features(spec, session, true); }

OpenedFeatureSession open_feature_session(FeatureRunSpec& spec) {
  OpenedFeatureSession out;
  MultiresSurface original = feature_hierarchy(spec);
  out.diagonal = bounding_diagonal(original.mesh(spec.levels));
  out.session = placed_features(spec, std::move(original));
  if (!spec.has_edit) return out;
  // The detail-preserving edit of the surface without features (Boier-Martin et al.); the
  // features drawn before it are attached by face and barycentric coordinates and ride on it,
  // those drawn after it are placed on the edited surface.
  const Timer timer;
  EditedHierarchy e = edited_hierarchy(*spec.editor, out.session->original());
  out.edit_s = timer.seconds();
  out.edit = e.summary;
  if (!is_success(e.summary.termination)) return out;
  out.session->edit_original() = std::move(e.edited);
  place_features_after_edit(spec, *out.session);
  return out;
}

namespace {

// The session's measurement as a run reports it: a row of features.csv per feature, the worst of
// them in runs.csv, and the verdict (a feature outside its tolerance: constraints_unmet naming
// it; a fold outranks it).
void report_profiles(const FeatureMeasurement& m, FeatureSession& session, MetricRow& row, const RunOutputs& out) {
  // Only the surface profile_on makes exact decides a verdict; the other is reported.
  const char* gated_on = feature::gates_name(feature::profile_gates(session.featured().profile_target()));
  int within = 0;
  double fine = 0, limit = 0, height = 0, width = 0;
  for (const feature::FeatureMeasure& f : m.features) {
    const feature::FeatureParams& q = session.features().at(f.id).params;
    const auto& a = f.fine;
    const auto& b = f.limit;
    out.add_row("features", {f.name, std::to_string(f.level), num(q.height), num(q.radius), num(q.right_radius()),
                             num(a.height_min), num(a.height_max), num(a.width_left), num(a.width_right), num(a.height_error),
                             num(a.width_error), num(a.profile_error), num(b.height_min), num(b.height_max), num(b.width_left),
                             num(b.width_right), num(b.height_error), num(b.width_error), num(b.profile_error),
                             f.within_tolerance ? "1" : "0", f.why, gated_on});
    within += f.within_tolerance ? 1 : 0;
    fine = std::max(fine, a.profile_error), limit = std::max(limit, b.profile_error);
    height = std::max({height, a.height_error, b.height_error});
    width = std::max({width, a.width_error, b.width_error});
  }
  row["features_within_tolerance"] = std::to_string(within);
  row["worst_profile_error_fine"] = num(fine);
  row["worst_profile_error_limit"] = num(limit);
  row["worst_height_error"] = num(height);
  row["worst_width_error"] = num(width);
  row["flipped_faces"] = std::to_string(m.folds.flipped.size());
  if (m.summary.termination != Termination::Converged) {
    row["termination"] = std::string(to_string(m.summary.termination));
    row["message"] = m.summary.message;
  }
}

}  // namespace

MetricRow execute_feature_run(FeatureRunSpec& spec, const RunOutputs& out) {
  MetricRow row;
  for (const auto& c : feature_metric_columns()) row[c] = "";
  row["implementation"] = std::string(to_string(spec.implementation));
  row["features"] = std::to_string(spec.features.size());
  row["unused_keys"] = spec.unused_keys_cell();
  row["levels"] = std::to_string(spec.levels);
  row["profile_on"] = std::string(feature::profile_target_names().name(spec.profile_target));
  row["termination"] = std::string(to_string(Termination::Converged));
  const Timer wall;
  reset_peak_rss();  // this run's own peak, not an earlier run's of the sweep
  try {
    if (spec.adaptive_sparse) {  // the uniform hierarchy never built (sparse_run.h)
      execute_sparse_feature_run(spec, out, row);
      row["time_s"] = num(wall.seconds());
      row["peak_rss_mb"] = num(peak_rss_mb());
      return row;
    }
    OpenedFeatureSession opened = open_feature_session(spec);
    FeatureSession& session = *opened.session;
    const double diag = opened.diagonal;
    if (opened.edit) {
      row["edit_s"] = num(opened.edit_s);
      if (!is_success(opened.edit->termination)) {
        row["termination"] = std::string(to_string(opened.edit->termination));
        row["message"] = "the edit: " + opened.edit->message;
        row["time_s"] = num(wall.seconds());
        return row;
      }
    }
    // Every design step evaluated (one when nothing is scheduled): the last one's time is apply_s.
    row["apply_s"] = num(run_feature_steps(spec, session, out));
    feature::FeaturedSurface& surface = session.featured();
    const MultiresSurface& result = session.surface();
    SurfaceMesh fine = result.mesh(spec.levels);
    const MatrixX3 d = fine.positions() - std::as_const(surface).original().mesh(spec.levels).positions();
    const Eigen::VectorXd norms = d.rowwise().norm();
    fine.vertex_data["displacement"] = d;
    fine.vertex_data["displacement_norm"] = norms;
    row["n_fine"] = std::to_string(fine.n_vertices());
    row["vertices_moved"] = std::to_string((norms.array() > 1e-12 * diag).count());
    row["max_displacement"] = num(norms.maxCoeff());
    row["triangles_uniform"] = std::to_string(fine.n_faces());
    int segments = 0;
    fs::create_directories(fs::path(out.dir) / "curves");
    // vtk/<run>_constraints.vtp: each curve on the surface it made (its finest-level attachment on
    // the result) and the outline of the features' neighbourhoods (where the displacement falls
    // to 1 % of the smallest requested height).
    ConstraintOverlay drawn;
    double smallest = std::numeric_limits<double>::infinity();
    for (const auto& [id, f] : surface.features()) smallest = std::min(smallest, std::abs(f.params.height));
    if (std::isfinite(smallest) && smallest > 0)
      for (const std::vector<Vec3>& line : contour_lines(fine, norms, 0.01 * smallest)) drawn.add_outline(line);
    const std::map<int, std::vector<Vec3>> on_finest = curves_on_finest_result(surface);
    for (const auto& [id, bc] : surface.base_curves()) {
      segments += static_cast<int>(bc.segments.size());
      // A closed curve's last segment ends at the first one's start: written once, as a loop.
      MatrixX3 X(static_cast<Eigen::Index>(bc.segments.size() + (bc.closed ? 0 : 1)), 3);
      for (std::size_t i = 0; i < bc.segments.size(); ++i) X.row(static_cast<Eigen::Index>(i)) = bc.segments[i].a.transpose();
      if (!bc.closed) X.row(X.rows() - 1) = bc.segments.back().b.transpose();
      write_polyline(Polyline{X, bc.closed}, (fs::path(out.dir) / "curves" /
                                          (out.run_id + "_" + file_name_part(surface.features().at(id).name) + ".obj")).string());
      drawn.add_curve(on_finest.at(id), bc.closed);
    }
    if (spec.vtk) drawn.write((fs::path(out.dir) / "vtk" / (out.run_id + "_constraints.vtp")).string());
    row["segments"] = std::to_string(segments);
    if (spec.adaptive) {
      int from = spec.levels;
      double angle = 90;
      for (const auto& f : spec.features) {
        from = std::min(from, f.curve.level);
        angle = std::min(angle, f.curve.params.flatness_angle_deg);
      }
      const SurfaceMesh adaptive = feature::adaptive_mesh(result, from, angle).mesh;
      long long faces = 0;
      for (int k = 0; k <= spec.levels; ++k) faces += result.mesh(k).n_faces();
      row["adaptive_faces_computed"] = std::to_string(faces);
      row["adaptive_evaluation"] = "uniform";  // sparse runs take execute_sparse_feature_run
      row["triangles_adaptive"] = std::to_string(adaptive.n_faces());
      fs::create_directories(fs::path(out.dir) / "adaptive");
      write_mesh(adaptive, (fs::path(out.dir) / "adaptive" / (out.run_id + ".obj")).string());
    }
    export_attachments(surface, out);
    if (spec.vtk) {
      const LimitSurface limit = export_levels_and_limit(surface, out);
      fine.vertex_data["limit_position"] = limit.positions;
      fine.vertex_data["limit_normal"] = limit.normals;
    }
    const FeatureMeasurement measured = session.measure();
    mark_flipped(fine, measured.folds);
    if (spec.vtk) write_vtp(fine, (fs::path(out.dir) / "vtk" / (out.run_id + ".vtp")).string());
    write_mesh(fine, out.final_path());
    report_profiles(measured, session, row, out);
  } catch (const OutputError& e) {  // results incomplete: not a finished run
    row["termination"] = std::string(to_string(Termination::OutputFailed));
    row["message"] = e.what();
  } catch (const Error& e) {  // validation applied the coarsest features only
    row["termination"] = std::string(to_string(Termination::InvalidInput));
    row["message"] = std::string("applying the features to the perturbed surface: ") + e.what();
  }
  row["time_s"] = num(wall.seconds());
  row["peak_rss_mb"] = num(peak_rss_mb());
  return row;
}

}  // namespace fairshape
