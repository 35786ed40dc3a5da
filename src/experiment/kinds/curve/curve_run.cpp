#include "fairshape/experiment/kinds/curve/curve_run.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "fairshape/core/summary.h"
#include "fairshape/core/config.h"
#include "fairshape/core/timer.h"
#include "fairshape/curve_design/curve_metrics.h"
#include "fairshape/curve_design/curve_plane.h"
#include "fairshape/curve_design/second_order.h"
#include "fairshape/curves/curve_sampling.h"
#include "fairshape/curve_design/wrinkle_scale.h"
#include "fairshape/curves/multires_polyline.h"
#include "fairshape/experiment/metric_format.h"
#include "fairshape/io/constraint_overlay.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/experiment/vtk_policy.h"
#include "fairshape/io/vtk_io.h"

namespace fairshape {
namespace fs = std::filesystem;
namespace {

int polygon_points(int n_points, bool closed, int levels, int level) {
  const int segments = (closed ? n_points : n_points - 1) >> (levels - level);
  return closed ? segments : segments + 1;
}

}  // namespace

CurveEditEntry read_curve_edit(Config& ec, const CurveRunSpec* on) {
  CurveEditEntry entry;
  CurveEdit& e = entry.whole;
  e.edit_level = ec.require<int>("level", "e: the level whose control points are moved (0 = coarsest)");
  e.wrinkle_level = ec.get_int("wrinkle_level", -1, -1, 64,
                               "w in [e, levels-1]: explicit length preservation at level w+1 (-1: none, §3 alone)");
  int m = 0;  // control points of level e (with `on`)
  if (on != nullptr) {
    const CurveRunSpec& s = *on;
    const std::string counts = "an open curve of 2^L·k + 1 points (a closed one of 2^L·k, k ≥ 3) has levels 0..L; " +
                               s.curve_path + " has " + std::to_string(s.curve.n_points()) + " points and " +
                               std::to_string(s.levels) + " levels";
    if (e.edit_level < 0 || e.edit_level > s.levels)
      throw InvalidConfig(ec.key_path("level") + ": " + std::to_string(e.edit_level) + " is outside the hierarchy (" + counts + ")");
    if (e.wrinkle_level != -1 && (e.wrinkle_level < e.edit_level || e.wrinkle_level >= s.levels))
      throw InvalidConfig(ec.key_path("wrinkle_level") + ": " + std::to_string(e.wrinkle_level) + " must lie in [e, levels-1] = [" +
                          std::to_string(e.edit_level) + ", " + std::to_string(s.levels - 1) + "] or be -1 (" + counts + ")");
    m = polygon_points(s.curve.n_points(), s.curve.closed, s.levels, e.edit_level);
  }
  for (Config mc : ec.child_list("moves", "control points moved at level e: [{index, by: [x, y, z]} | {index, chord_scale}]")) {
    CurveMove mv;
    mv.index = mc.require<int>("index", "level-e control point (negative: from the end, -1 = last)");
    if (on != nullptr && (mv.index >= m || mv.index < -m))
      throw InvalidConfig(mc.key_path("index") + ": " + std::to_string(mv.index) + " is not on the level-" +
                          std::to_string(e.edit_level) + " polygon of " + std::to_string(m) + " points");
    const auto by = mc.get<std::vector<double>>("by", {}, "offset [x, y, z] (or [x, y])");
    mv.chord_scale = mc.get_number("chord_scale", 0, 0, 1e6,
                                   "move along the chord from control point 0 so the chord becomes this many times "
                                   "as long (< 1 compresses, > 1 stretches)");
    mc.check_no_unknown_keys();
    if (by.empty() == (mv.chord_scale == 0) && !mc.documenting())
      throw InvalidConfig(mc.path() + ": give exactly one of `by` and `chord_scale`");
    if (!by.empty() && by.size() != 2 && by.size() != 3)
      throw InvalidConfig(mc.key_path("by") + ": expected [x, y] or [x, y, z]");
    for (std::size_t c = 0; c < by.size(); ++c) mv.offset[static_cast<int>(c)] = by[c];
    e.moves.push_back(mv);
  }
  entry.drag_steps = ec.get_int("drag_steps", 1, 1, 100000,
                                 "editing loops the moves are split into, each from the curve the previous one left");
  ec.check_no_unknown_keys();
  return entry;
}

namespace {

// The solver block: common tolerances, then one sub-block per solver name; every present
// sub-block is validated so sweeping solver.type stays valid, and recorded as unused unless
// it is the chosen solver's.
void read_solver(Config& oc, CurveEditSettings& st, RunBasics& basics, std::string& solver_type) {
  const auto& reg = curve_components().solvers;
  Config sc = oc.child("solver", "length solver: {type, length_tolerance, stationarity_tolerance, max_solves, <type>: {...}}");
  solver_type = sc.get_choice("type", "linearized", reg.names(), "length solver");
  for (const auto& name : reg.names())
    if (name != solver_type && sc.has(name)) {
      (void)reg.create(name, reg.has(name, basics.implementation) ? basics.implementation : Backend::Optimized, sc);
      basics.note_unused(Config(sc.node()[name], sc.key_path(name)));
    }
  st.solver = reg.create(solver_type, basics.implementation, sc);
  sc.check_no_unknown_keys();
}

void read_optimization(Config& root, CurveEditSettings& s, const Polyline& curve, const std::string& curve_name, RunBasics& basics,
                       std::string& solver_type) {
  const CurveComponents& cc = curve_components();
  Config oc = root.child("optimization", "the length-constrained smoothing that ends every editing loop");
  s.beta = oc.get_number("beta", 0.5, 0, 1, "Sauvage et al. eq. 2: (1-beta)·smoothness + beta·distance to C_A");
  std::vector<std::string> smooth = cc.energies.names();
  smooth.erase(std::remove(smooth.begin(), smooth.end(), "attractor_distance"), smooth.end());
  const std::string sm = oc.get_choice("smoothness", "bending", smooth, "the smoothness energy");
  Config none;
  s.smoothness = cc.energies.create(sm, basics.implementation, none);
  bool has_lengths = false;
  std::string total_key;  // the total_length entry's key, when there is one
  for (Config k : oc.child_list("constraints", "constraints: [{type: segment_lengths} | {type: total_length, value}, {type: pin, points: ...}]")) {
    const std::string type = k.get_choice("type", "segment_lengths", cc.constraints.names(), "constraint kind");
    s.constraints.push_back(cc.constraints.create(type, basics.implementation, k));
    k.check_no_unknown_keys();
    has_lengths |= type == "segment_lengths";
    if (type == "total_length") {
      if (!total_key.empty()) throw InvalidConfig(k.key_path("type") + ": a second total_length (" + total_key + " is one); keep one");
      total_key = k.key_path("type");
      if (s.editing.solve_region == SolveRegion::Support)
        throw InvalidConfig(total_key + ": total_length couples every point of the curve, so it is not solved on the edit's "
                            "support (editing.solve_region: support, the default); set editing.solve_region: curve");
    }
    if (type == "tangent" && s.editing.solve_region == SolveRegion::Support)
      throw InvalidConfig(k.key_path("type") + ": tangent constraints are not solved on the edit's support yet "
                          "(src/curve_design/edit_window.h); set editing.solve_region: curve");
  }
  if (s.constraints.empty()) {
    s.constraints.push_back(cc.constraints.create("segment_lengths", basics.implementation, none));
    has_lengths = true;
  }
  if (has_lengths && !total_key.empty())
    throw InvalidConfig(total_key + ": total_length and segment_lengths together: the total is the sum of the segments (a "
                        "dependent row); keep one — segment_lengths keeps every segment, total_length only their sum");
  if (!has_lengths && total_key.empty())
    throw InvalidConfig(oc.key_path("constraints") + ": lengths are what this editor preserves; include {type: segment_lengths} "
                        "(every segment's length) or {type: total_length} (the curve's total length)");
  read_solver(oc, s, basics, solver_type);
  // The dense second-order check is O((3N)³): refused where it would dominate every solve
  // (papers/sauvage/README.md, "Second-order checks cheaper than the solve").
  if (s.solver->tolerances().second_order == SecondOrderMode::Dense && curve.n_points() > kSecondOrderDenseLimit) {
    std::ostringstream m;
    m << oc.key_path("solver") << ".second_order: dense eigen-decomposes the reduced Hessian (O(n^3)) and takes curves of up to "
      << kSecondOrderDenseLimit << " points; " << curve_name << " has " << curve.n_points()
      << " — use inertia (the default: the same verdict from the banded KKT factor's inertia, O(n)) or off";
    throw InvalidConfig(m.str());
  }
  if (!total_key.empty() && !s.solver->takes_dense_rows()) {
    std::string takers;
    Config none;
    for (const auto& name : cc.solvers.names())
      if (cc.solvers.create(name, Backend::Optimized, none)->takes_dense_rows()) takers += (takers.empty() ? "" : ", ") + name;
    throw InvalidConfig(oc.key_path("solver") + ".type: " + solver_type + " does not take the total_length constraint (" +
                        total_key + "); the solvers that do: " + takers);
  }
  oc.check_no_unknown_keys();
}

// How the loop keeps edits local (papers/sauvage/README.md).
EditingOptions read_editing(Config& root, bool& accept_partial_edit) {
  EditingOptions o;
  Config c = root.child("editing", "how the editing loop keeps an edit local: {explicit_step, details, solve_region}");
  const std::string step = c.get_choice("explicit_step", "local", {"local", "sweep"},
                                        "stretched level-w segments: local (only the edit's support moves) or sweep "
                                        "(the first implementation: the rest follows the dragged point like a rope)");
  const std::string details = c.get_choice("details", "local_frames", {"global", "local_frames"},
                                           "details in world coordinates (the paper) or in their coarse segment's frame");
  const std::string region = c.get_choice("solve_region", "support", {"support", "curve"},
                                          "the §3 optimization over the edit's support (the rest held) or the whole curve");
  const std::string plane = c.get_choice("plane", "keep", {"keep", "free"},
                                         "keep: a planar problem (curve, edit and constraints in one plane) is solved in its "
                                         "plane; free: every point has three unknowns, so a planar curve may leave its plane");
  accept_partial_edit =
      c.get_choice("partial_edit", "fail", {"fail", "accept"},
                   "an edit not honoured — handles pulled back or returned (edit_undone), attracting-curve lengths left "
                   "wrong by the explicit step (constraints_unmet): fail ends the run so (exit 3); accept ends it converged, "
                   "the message saying what happened") == "accept";
  c.check_no_unknown_keys();
  o.plane = plane == "keep" ? PlaneMode::Keep : PlaneMode::Free;
  o.explicit_step = step == "local" ? ExplicitStep::Local : ExplicitStep::Sweep;
  o.details = details == "local_frames" ? DetailFrames::LocalFrames : DetailFrames::Global;
  o.solve_region = region == "support" ? SolveRegion::Support : SolveRegion::Curve;
  return o;
}

}  // namespace

bool is_curve_config(const YAML::Node& c) { return c["input"] && c["input"].IsMap() && c["input"]["curve"]; }

CurveEditSettings read_curve_settings(Config& root, const Polyline& curve, const std::string& curve_name, RunBasics& basics,
                                      std::string& solver_type) {
  CurveEditSettings s;
  s.backend = basics.implementation;
  s.editing = read_editing(root, s.accept_partial_edit);
  read_optimization(root, s, curve, curve_name, basics, solver_type);
  return s;
}

namespace {
// The point counts nearest n (below and above) that allow 4 levels, for messages.
std::string nearest_level_counts(int n, bool closed) {
  const int step = 16, extra = closed ? 0 : 1;  // 2^4·k (+ 1)
  const int below = std::max(closed ? 3 * step : step, (n - extra) / step * step) + extra, above = below + step;
  return std::to_string(below) + " or " + std::to_string(above) + " for 4 levels";
}
}  // namespace

// While documenting the keys: a straight curve of 2^8 + 1 points, so the reads that depend on
// the curve run.
static Polyline documenting_stand_in() {
  Polyline p;
  p.points = MatrixX3::Zero(257, 3);
  p.points.col(0) = Eigen::VectorXd::LinSpaced(257, 0.0, 1.0);
  return p;
}

// Every key of the run read from `root` (parse_config: unknown keys reported together).
static CurveRunSpec read_curve_run(const std::vector<std::string>& dirs, Config& root) {
  CurveRunSpec s;
  static_cast<RunBasics&>(s) = read_run_basics(root);
  Config in = root.child("input", "input curve");
  s.curve_path = read_input_path(in, "curve", "polyline OBJ (v and l lines)", dirs);
  const int levels = in.get_int("levels", -1, -1, 62, "hierarchy depth (-1: as many as the point count allows)");
  const int resample = in.get_int("resample", 0, 0, 1 << 24,
                                  "resample the curve to this many points, equally spaced in arc length (0: as read); "
                                  "2^L·k + 1 points (closed: 2^L·k) give L levels");
  in.check_no_unknown_keys();
  try {
    s.curve = in.documenting() ? documenting_stand_in() : read_polyline(s.curve_path);
    if (resample > 0) s.curve.points = resample_polyline(s.curve.points, s.curve.closed, resample + (s.curve.closed ? 1 : 0))
                                           .topRows(resample);
  } catch (const Error& e) {
    throw InvalidConfig(in.key_path(resample > 0 ? "resample" : "curve") + ": " + e.what());
  }
  const int most = max_polyline_levels(s.curve.n_points(), s.curve.closed);
  // A point count with no coarser level leaves the multiresolution out: never silently.
  if (levels < 0 && most == 0)
    throw InvalidConfig(in.key_path("curve") + ": " + s.curve_path + " has " + std::to_string(s.curve.n_points()) +
                        " points, which allow no coarser level (" + (s.curve.closed ? "2^L·k points, k ≥ 3" : "2^L·k + 1 points") +
                        " give L levels): resample it (input.resample: " + nearest_level_counts(s.curve.n_points(), s.curve.closed) +
                        ") or ask input.levels: 0 to edit it as it is");
  s.levels = levels < 0 ? most : levels;
  if (s.levels > most)
    throw InvalidConfig(in.key_path("levels") + ": " + std::to_string(s.levels) + " levels need " +
                        (s.curve.closed ? "2^L·k points (k ≥ 3)" : "2^L·k + 1 points") + "; " + s.curve_path + " has " +
                        std::to_string(s.curve.n_points()) + " points, which allow " + std::to_string(most));
  for (Config ec : root.child_list("edits", "editing loops applied in order: [{level, wrinkle_level, moves, drag_steps}]")) {
    const CurveEditEntry entry = read_curve_edit(ec, &s);
    for (CurveEdit& e : drag_steps(entry.whole, entry.drag_steps)) s.edits.push_back(std::move(e));
  }
  if (s.edits.empty()) throw InvalidConfig("edits: at least one edit is required" + root.misspelling_of("edits"));
  s.settings = read_curve_settings(root, s.curve, s.curve_path, s, s.solver_type);
  for (auto& e : s.edits) e.options = s.settings.editing;
  Config out = root.child("output", "what each run writes");
  s.vtk = read_vtk_policy(out, "every stage of every edit");
  s.final_curve = out.get<bool>("final_curve", true, "write final.obj (final/<run_id>.obj in sweeps)");
  s.wrinkle_scale = out.get<bool>("wrinkle_scale", true,
                                  "runs.csv's wrinkle_amplitude, wrinkle_wavelength(_segments): an FFT of the curve per run "
                                  "(false: left empty)");
  out.check_no_unknown_keys();
  root.check_no_unknown_keys();
  return s;
}

std::vector<OptionDoc> CurveRunSpec::keys() {
  return document_keys([](Config& root) { (void)read_curve_run({}, root); });
}

CurveRunSpec CurveRunSpec::from_config(const YAML::Node& run_config, const std::vector<std::string>& dirs) {
  return parse_config(run_config, [&](Config& root) { return read_curve_run(dirs, root); });
}

const std::vector<std::string>& curve_metric_columns() {
  static const std::vector<std::string> cols{
      "n_points", "edits", "length_error_max", "length_error_rms", "total_length_change", "bending_energy",
      "distance_to_attractor", "wrinkles", "wrinkle_amplitude", "wrinkle_wavelength", "wrinkle_wavelength_segments",
      "length_constraint", "total_length_asked", "total_length_error", "segment_stretch_min", "segment_stretch_max",
      "attractor_length_error", "moved_outside_support", "attractor_moved_outside_support", "solves", "outer_iterations", "stationarity", "min_reduced_hessian_eig", "saddle_escapes",
      "plane", "out_of_plane", "second_order_space", "handle_reach", "explicit_length_error", "unplaceable_midpoints", "self_crossings",
      "explicit_s", "solve_s", "time_s", "unused_keys", "termination", "message"};
  return cols;
}

const std::vector<std::string>& curve_step_columns() {
  static const std::vector<std::string> cols{
      "edit", "stage", "length_error_max", "length_error_rms", "total_length_change", "bending_energy",
      "distance_to_attractor", "wrinkles", "solves", "time_s", "drag_step"};
  return cols;
}

const std::vector<std::string>& curve_iteration_columns() {
  static const std::vector<std::string> cols{"edit", "solve", "length_error", "stationarity", "objective", "seconds"};
  return cols;
}

namespace {

const char* const kStages[] = {"reference", "edited", "attracting", "final"};

// `moved`: the edit's handles (fine-level indices), drawn over the stage from where they were
// on the reference curve to where the edit put them (<stem>_constraints.vtp).
void write_stage(const CurveRunSpec& spec, const RunOutputs& out, int edit, const char* stage, const MatrixX3& X,
                 const MatrixX3& reference, const EditStages& stages) {
  const std::string stem = out.run_id + "_edit" + std::to_string(edit) + "_" + stage;
  const Polyline c{X, spec.curve.closed};
  const fs::path curves = fs::path(out.dir) / "curves";
  fs::create_directories(curves);
  write_polyline(c, (curves / (stem + ".obj")).string());
  if (spec.vtk == VtkPolicy::All || (spec.vtk == VtkPolicy::Final && std::string(stage) == "final")) {
    const std::string vtk = (fs::path(out.dir) / "vtk" / stem).string();
    write_vtp(c, {{"displacement", Eigen::MatrixXd(X - reference)}}, vtk + ".vtp");
    ConstraintOverlay handles;
    for (int p : stages.moved_points)
      handles.add_handle(stages.edited.row(p).transpose(), (stages.edited.row(p) - stages.reference.row(p)).transpose());
    handles.write(vtk + "_constraints.vtp");
  }
}

std::vector<std::string> step_row(int edit, const CurveEdit& e, const char* stage, const CurveMetrics& m, const std::string& solves,
                                  const std::string& time) {
  return {std::to_string(edit), stage, num(m.length_error_max), num(m.length_error_rms),
          num(m.total_length_change), num(m.bending_energy), num(m.distance_to_attractor), std::to_string(m.wrinkles),
          solves, time, std::to_string(e.drag_step) + "/" + std::to_string(e.drag_steps)};
}

// steps.csv and iterations.csv rows and the stages' curves of one step.
void write_step(const CurveRunSpec& spec, const RunOutputs& out, const CurveStep& step, const Eigen::VectorXd& original) {
  const EditStages& last = step.stages;
  const MatrixX3* stage_points[] = {&last.reference, &last.edited, &last.attracting, &last.final};
  const CurveEdit& e = spec.edits[static_cast<std::size_t>(step.index)];
  for (int st = 0; st < 4; ++st) {
    const bool fin = st == 3;
    const CurveMetrics m = fin ? step.checks.metrics : measure_curve(*stage_points[st], spec.curve.closed, original, last.attracting);
    out.add_row("steps", step_row(step.index, e, kStages[st], m, fin ? std::to_string(last.solve.solves) : "",
                                  fin ? num(last.total_s) : ""));
    if (spec.vtk != VtkPolicy::None) write_stage(spec, out, step.index, kStages[st], *stage_points[st], last.reference, last);
  }
  for (const LengthSolveStep& h : last.solve.history)
    out.add_row("iterations", {std::to_string(step.index), std::to_string(h.solves), num(h.length_error), num(h.stationarity),
                               num(h.objective), num(h.seconds)});
}

// The columns of the last step's result and the session's verdict.
void fill_result(MetricRow& row, const CurveRunSpec& spec, const CurveSession& session) {
  const CurveStep& last = *session.last();
  const CurveStepChecks& c = last.checks;
  const CurveSessionTotals& t = session.totals();
  const LengthSolveReport& solve = last.stages.solve;
  row["length_error_max"] = num(c.metrics.length_error_max);
  row["length_error_rms"] = num(c.metrics.length_error_rms);
  row["total_length_change"] = num(c.metrics.total_length_change);
  // What the last solve was asked to keep, next to what it reached.
  row["length_constraint"] = last.stages.length_mode == LengthMode::Total ? "total_length" : "segment_lengths";
  row["total_length_asked"] = num(last.stages.total_length_asked);
  row["total_length_error"] = num(c.total_length_error);
  row["segment_stretch_min"] = num(c.segment_stretch_min);
  row["segment_stretch_max"] = num(c.segment_stretch_max);
  row["bending_energy"] = num(c.metrics.bending_energy);
  row["distance_to_attractor"] = num(c.metrics.distance_to_attractor);
  row["wrinkles"] = std::to_string(c.metrics.wrinkles);
  if (spec.wrinkle_scale) {  // what length preservation added to the last edit's attracting curve
    const WrinkleScale w = wrinkle_scale(session.current().points, last.stages.attracting, spec.curve.closed);
    row["wrinkle_amplitude"] = num(w.amplitude);
    row["wrinkle_wavelength"] = num(w.wavelength);
    row["wrinkle_wavelength_segments"] = num(w.wavelength_segments);
  }
  row["attractor_length_error"] = num(c.attractor_length_error);
  if (!solve.history.empty()) row["stationarity"] = num(solve.history.back().stationarity);
  // Second order (curve_design/second_order.h): ≥ 0 (to rounding) at a true local minimum.
  // Empty when the solve did not end at a judged point; not_checked with second_order: off,
  // not_estimated when the check failed (the message says so).
  if (!std::isnan(solve.min_reduced_hessian_eig)) row["min_reduced_hessian_eig"] = num(solve.min_reduced_hessian_eig);
  else if (solve.converged())
    row["min_reduced_hessian_eig"] =
        session.settings().solver->tolerances().second_order == SecondOrderMode::Off ? "not_checked" : "not_estimated";
  row["saddle_escapes"] = std::to_string(solve.saddle_escapes);
  const SolveSummary outcome = session.outcome();
  row["termination"] = std::string(to_string(outcome.termination));
  row["message"] = outcome.message;
  row["handle_reach"] = num(t.handle_reach);
  row["explicit_length_error"] = num(t.explicit_length_error);
  row["unplaceable_midpoints"] = std::to_string(t.unplaceable_midpoints);
  const bool planar = session.original_plane().planar;
  row["plane"] = !planar ? "not_planar" : t.every_step_in_plane ? "kept" : "free";
  row["second_order_space"] = last.stages.solved_in_plane ? "in_plane" : "3d";
  if (planar) {
    row["out_of_plane"] = num(c.out_of_plane);
    row["self_crossings"] = std::to_string(c.self_crossings);
  }
}
}  // namespace

MetricRow execute_curve_run(CurveRunSpec& spec, const RunOutputs& out) {
  MetricRow row;
  for (const auto& c : curve_metric_columns()) row[c] = "";
  row["implementation"] = std::string(to_string(spec.implementation));
  row["solver.type"] = spec.solver_type;
  row["n_points"] = std::to_string(spec.curve.n_points());
  row["unused_keys"] = spec.unused_keys_cell();
  row["termination"] = std::string(to_string(Termination::Converged));
  const Timer wall;
  CurveSession session(spec.curve, spec.levels, std::move(spec.settings));
  try {
    const Eigen::VectorXd original = segment_lengths(spec.curve.points, spec.curve.closed);
    for (const CurveEdit& e : spec.edits) {
      const CurveStep step = session.edit(e);
      write_step(spec, out, step, original);
      if (!step.stages.solve.converged()) break;  // the run stops at the first failed solve
    }
    fill_result(row, spec, session);
    if (spec.final_curve) write_polyline(session.current(), out.final_path());
  } catch (const OutputError& e) {  // results incomplete: not a finished run
    row["termination"] = std::string(to_string(Termination::OutputFailed));
    row["message"] = e.what();
  } catch (const Error& e) {
    row["termination"] = std::string(to_string(Termination::InvalidInput));
    row["message"] = "edit " + std::to_string(session.totals().steps) + ": " + e.what();
  }
  const CurveSessionTotals& t = session.totals();
  row["edits"] = std::to_string(t.steps);
  row["moved_outside_support"] = num(t.moved_outside_support);
  row["attractor_moved_outside_support"] = num(t.attractor_moved_outside_support);
  row["solves"] = std::to_string(t.solves);
  row["outer_iterations"] = std::to_string(t.outer_iterations);
  row["explicit_s"] = num(t.explicit_s);
  row["solve_s"] = num(t.solve_s);
  row["time_s"] = num(t.steps ? t.time_s : wall.seconds());
  return row;
}

}  // namespace fairshape
