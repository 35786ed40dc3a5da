// The curve editor of Sauvage, Hahmann and Bonneau, "Length preserving multiresolution editing
// of curves" (src/curves, src/curve_design): a polyline decomposed by the lazy-wavelet filter
// bank, and the session (curve_session.h) whose steps run the editing loop of §4.1 to its
// length-constrained optimization (§3). Its keywords are a curve config's blocks, read by the
// run kind's own reader (src/experiment/kinds/curve/curve_run.cpp): energies, constraints and
// solvers by name, every option checked, an unknown one refused naming the valid ones.
// Copies: the points come in as a new n×3 matrix (2-D curves with z = 0, as the library keeps
// them); every stage comes back as a new n×3 array (the Python side drops z for 2-D curves).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>

#include "bindings.h"
#include "checks.h"
#include "convert.h"
#include "fairshape/curve_design/curve_components.h"
#include "fairshape/curve_design/curve_session.h"
#include "fairshape/curves/multires_polyline.h"
#include "fairshape/experiment/kinds/curve/curve_run.h"

namespace py = pybind11;

namespace fairshape::python {
namespace {

Polyline polyline_arg(const Eigen::Ref<const Eigen::MatrixXd>& points, bool closed) {
  if (points.cols() != 2 && points.cols() != 3)
    throw InvalidInput("curve points: expected an n×2 or n×3 array, got " + std::to_string(points.rows()) + "×" +
                       std::to_string(points.cols()));
  if (!points.allFinite()) throw InvalidInput("curve points: not every coordinate is finite");
  Polyline c;
  c.closed = closed;
  c.points = MatrixX3::Zero(points.rows(), 3);
  c.points.leftCols(points.cols()) = points;
  return c;
}

int levels_arg(const Polyline& c, int levels) {
  const int most = max_polyline_levels(c.n_points(), c.closed);
  if (levels < 0) return most;
  if (levels > most)
    throw InvalidInput("curve: " + std::to_string(levels) + " levels need " +
                       (c.closed ? "2^L·k points (k ≥ 3)" : "2^L·k + 1 points") + "; the curve has " +
                       std::to_string(c.n_points()) + " points, which allow " + std::to_string(most));
  return levels;
}

Eigen::MatrixXd curve_level(const Eigen::Ref<const Eigen::MatrixXd>& points, bool closed, int levels, int level,
                            const std::string& implementation) {
  const Backend backend = backend_arg(implementation);
  const Polyline c = polyline_arg(points, closed);
  const int L = levels_arg(c, levels);
  if (level < 0 || level > L)
    throw InvalidIndex("curve level " + std::to_string(level) + " is not in the hierarchy (levels 0.." + std::to_string(L) + ")");
  return checked(Eigen::MatrixXd(reconstruct(decompose(c, L, backend), level, backend).points), "Curve.level");
}

Eigen::MatrixXd curve_details(const Eigen::Ref<const Eigen::MatrixXd>& points, bool closed, int levels, int level,
                              const std::string& implementation) {
  const Backend backend = backend_arg(implementation);
  const Polyline c = polyline_arg(points, closed);
  const int L = levels_arg(c, levels);
  if (level < 0 || level >= L)
    throw InvalidIndex("curve details " + std::to_string(level) + ": the hierarchy has d^0..d^" + std::to_string(L - 1));
  return checked(Eigen::MatrixXd(decompose(c, L, backend).details[static_cast<std::size_t>(level)]), "Curve.details");
}

// The session's keywords as a curve config's editing: and optimization: blocks, read by the
// run kind's reader (one parser for both front ends). Options a config would record as unused
// (a solver's block that is not the chosen solver's) are refused: a keyword does something.
CurveEditSettings settings_arg(const Polyline& curve, Backend backend, const py::dict& options) {
  return parse_config(to_yaml(options, "CurveSession"), [&](Config& root) {
    RunBasics basics;
    basics.implementation = backend;
    std::string solver_type;
    CurveEditSettings settings = read_curve_settings(root, curve, "the session's curve", basics, solver_type);
    root.check_no_unknown_keys();
    if (!basics.unused_keys.empty())
      throw InvalidConfig(basics.unused_keys.front() + ": the options of a solver that is not the chosen one (" + solver_type +
                          "); give them with its type");
    return settings;
  });
}

// An edit's keywords as an edits: entry; the level and control points checked on the session's
// hierarchy (an index off its level's polygon is an InvalidIndex).
CurveEditEntry edit_arg(const CurveSession& session, const py::dict& entry, const char* who) {
  const CurveEditEntry e = parse_config(to_yaml(entry, who), [](Config& c) { return read_curve_edit(c, nullptr); });
  const int L = session.levels(), level = e.whole.edit_level;
  if (level < 0 || level > L)
    throw InvalidIndex(std::string(who) + ": level " + std::to_string(level) + " is outside the hierarchy (levels 0.." +
                       std::to_string(L) + ")");
  const int m = session.control_points(level);
  for (const CurveMove& mv : e.whole.moves)
    if (mv.index >= m || mv.index < -m)
      throw InvalidIndex(std::string(who) + ": index " + std::to_string(mv.index) + " is not on the level-" +
                         std::to_string(level) + " polygon of " + std::to_string(m) + " points");
  return e;
}

py::object optional(double v) { return std::isnan(v) ? py::object(py::none()) : py::cast(v); }

// A step as the dict fairshape.CurveStep is made from.
py::dict step_dict(const CurveStep& s) {
  const EditStages& st = s.stages;
  const CurveStepChecks& c = s.checks;
  const std::string outcome = std::string(to_string(s.summary.termination)) + ": " + s.summary.message;
  for (const auto* stage : {&st.reference, &st.edited, &st.attracting, &st.final})
    finite_result(*stage, "CurveSession: a stage of the edit (" + outcome + ")");
  py::dict checks;
  checks["length_error_max"] = c.metrics.length_error_max;
  checks["length_error_rms"] = c.metrics.length_error_rms;
  checks["total_length_change"] = c.metrics.total_length_change;
  checks["bending_energy"] = c.metrics.bending_energy;
  checks["distance_to_attractor"] = c.metrics.distance_to_attractor;
  checks["wrinkles"] = c.metrics.wrinkles;
  checks["length_constraint"] = std::string(st.length_mode == LengthMode::Total ? "total_length" : "segment_lengths");
  checks["total_length_asked"] = st.total_length_asked;
  checks["total_length_error"] = c.total_length_error;
  checks["segment_stretch_min"] = c.segment_stretch_min;
  checks["segment_stretch_max"] = c.segment_stretch_max;
  checks["attractor_length_error"] = c.attractor_length_error;
  checks["moved_outside_support"] = c.moved_outside_support;
  checks["attractor_moved_outside_support"] = c.attractor_moved_outside_support;
  checks["handle_reach"] = c.handle_reach;
  checks["overstretch"] = c.overstretch < 0 ? py::object(py::none()) : py::cast(c.overstretch);
  checks["out_of_plane"] = optional(c.out_of_plane);
  checks["left_plane"] = c.left_plane;
  checks["self_crossings"] = c.self_crossings < 0 ? py::object(py::none()) : py::cast(c.self_crossings);
  checks["new_self_crossings"] = c.self_crossings < 0 ? 0 : std::max(0, c.self_crossings - c.original_self_crossings);
  checks["solved_in_plane"] = st.solved_in_plane;
  checks["explicit_length_error"] = st.explicit_step.length_error;
  checks["explicit_pull_back"] = st.explicit_step.worst_pull_back;
  checks["explicit_unreachable_chains"] = st.explicit_step.unreachable_chains;
  checks["unplaceable_midpoints"] = st.explicit_step.unplaceable_midpoints;
  checks["stationarity"] = st.solve.history.empty() ? py::object(py::none()) : py::cast(st.solve.history.back().stationarity);
  checks["min_reduced_hessian_eig"] = optional(st.solve.min_reduced_hessian_eig);
  checks["saddle_escapes"] = st.solve.saddle_escapes;
  checks["length_error"] = st.solve.length_error;
  py::dict out;
  out["index"] = s.index;
  out["drag_step"] = s.drag_step;
  out["drag_steps"] = s.drag_steps;
  put_summary(out, s.summary);
  out["solve_converged"] = st.solve.converged();
  out["solves"] = st.solve.solves;
  out["outer_iterations"] = st.solve.outer_iterations;
  out["solve_s"] = s.solve_s;
  out["check_s"] = s.check_s;
  out["explicit_s"] = st.explicit_s;
  out["moved_points"] = st.moved_points;
  out["checks"] = checks;
  out["reference"] = py::cast(st.reference);
  out["edited"] = py::cast(st.edited);
  out["attracting"] = py::cast(st.attracting);
  out["final"] = py::cast(st.final);
  return out;
}

// The session's verdict so far and its totals (a run's termination, message and counts).
py::dict outcome_dict(const CurveSession& session) {
  const SolveSummary s = session.outcome();
  const CurveSessionTotals& t = session.totals();
  py::dict out;
  put_summary(out, s);
  out["steps"] = t.steps;
  out["solves"] = t.solves;
  out["outer_iterations"] = t.outer_iterations;
  out["handle_reach"] = t.handle_reach;
  out["time_s"] = t.time_s;
  out["explicit_s"] = t.explicit_s;
  out["solve_s"] = t.solve_s;
  out["check_s"] = t.check_s;
  return out;
}

}  // namespace

void bind_curves(py::module_& m) {
  m.def("curve_max_levels", [](int n_points, bool closed) { return max_polyline_levels(n_points, closed); },
        py::arg("n_points"), py::arg("closed") = false,
        "Levels a curve of n_points allows: open 2^L·k + 1 points (k ≥ 1), closed 2^L·k (k ≥ 3).");
  m.def("_curve_level", &curve_level, py::arg("points"), py::arg("closed"), py::arg("levels"), py::arg("level"),
        py::arg("implementation"), "The curve hierarchy's level as points; call fairshape.Curve.level().");
  m.def("_curve_details", &curve_details, py::arg("points"), py::arg("closed"), py::arg("levels"), py::arg("level"),
        py::arg("implementation"), "The curve hierarchy's details d^j; call fairshape.Curve.details().");
  py::class_<CurveSession>(m, "_CurveSession", "The curve session's C++ half; use fairshape.CurveSession.")
      .def(py::init([](const Eigen::Ref<const Eigen::MatrixXd>& points, bool closed, int levels, const std::string& implementation,
                       const py::dict& options) {
             const Backend backend = backend_arg(implementation);
             Polyline curve = polyline_arg(points, closed);
             const int L = levels_arg(curve, levels);
             CurveEditSettings settings = settings_arg(curve, backend, options);
             return CurveSession(std::move(curve), L, std::move(settings));
           }),
           py::arg("points"), py::arg("closed"), py::arg("levels"), py::arg("implementation"), py::arg("options"))
      .def("edit", [](CurveSession& s, const py::dict& entry) {
             const CurveEditEntry e = edit_arg(s, entry, "CurveSession.edit");
             if (e.drag_steps != 1) throw InvalidConfig("CurveSession.edit: one editing loop; drag_step() takes drag_steps");
             CurveStep step;
             {
               py::gil_scoped_release release;
               step = s.edit(e.whole);
             }
             return step_dict(step);
           }, py::arg("entry"))
      .def("drag_step", [](CurveSession& s, const py::dict& entry) {
             const CurveEditEntry e = edit_arg(s, entry, "CurveSession.drag_step");
             CurveStep step;
             {
               py::gil_scoped_release release;
               step = s.drag_step(e.whole, e.drag_steps);
             }
             return step_dict(step);
           }, py::arg("entry"))
      .def_property_readonly("points", [](const CurveSession& s) { return Eigen::MatrixXd(s.current().points); })
      .def_property_readonly("levels", &CurveSession::levels)
      .def("outcome", &outcome_dict);
  m.def("curve_components", [] {
    const CurveComponents& cc = curve_components();
    py::dict d;
    d["energies"] = cc.energies.names();
    d["constraints"] = cc.constraints.names();
    d["solvers"] = cc.solvers.names();
    return d;
  }, "Names of the curve editor's registered energies, constraints and length solvers.");
}

}  // namespace fairshape::python
