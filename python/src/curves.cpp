// The curve editor of Sauvage, Hahmann and Bonneau, "Length preserving multiresolution editing
// of curves" (src/curves, src/curve_design): a polyline decomposed by the lazy-wavelet filter
// bank, control points of a level moved, and the editing loop of §4.1 run to its
// length-constrained optimization (§3), read exactly as a curve config's blocks are
// (src/experiment/kinds/curve/curve_run.cpp): energies, constraints and solvers by name, every
// option checked, an unknown one refused naming the valid ones.
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
#include "fairshape/curve_design/curve_metrics.h"
#include "fairshape/curve_design/editing_loop.h"
#include "fairshape/curves/multires_polyline.h"

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

EditingOptions editing_arg(const std::string& step, const std::string& details, const std::string& region) {
  const auto bad = [](const char* key, const std::string& v, const char* valid) {
    return InvalidConfig(std::string(key) + " '" + v + "': expected " + valid);
  };
  if (step != "local" && step != "sweep") throw bad("explicit_step", step, "'local' or 'sweep'");
  if (details != "local_frames" && details != "global") throw bad("details", details, "'local_frames' or 'global'");
  if (region != "support" && region != "curve") throw bad("solve_region", region, "'support' or 'curve'");
  EditingOptions o;
  o.explicit_step = step == "local" ? ExplicitStep::Local : ExplicitStep::Sweep;
  o.details = details == "local_frames" ? DetailFrames::LocalFrames : DetailFrames::Global;
  o.solve_region = region == "support" ? SolveRegion::Support : SolveRegion::Curve;
  return o;
}

// The solver block of a curve config from keyword arguments: the tolerances every solver
// shares at the top, the rest in the solver's own sub-block (where its factory reads them).
std::unique_ptr<LengthSolver> solver_arg(const std::string& type, const py::dict& options, Backend backend) {
  const auto& reg = curve_components().solvers;
  py::dict block, own;
  for (auto [k, v] : options) {
    const std::string key = py::str(k);
    if (key == "length_tolerance" || key == "stationarity_tolerance" || key == "max_solves" || key == "second_order")
      block[k] = v;
    else own[k] = v;
  }
  if (!own.empty()) block[type.c_str()] = own;
  Config sc = to_config(block, "solver");
  auto solver = reg.create(type, backend, sc);
  sc.check_no_unknown_keys();
  return solver;
}

struct CurveTerms {
  std::unique_ptr<CurveEnergy> smoothness;
  std::vector<std::unique_ptr<CurveConstraintKind>> constraints;
  bool total = false;
};

// curve_run.cpp's read_optimization checks, on constraint dicts.
CurveTerms terms_arg(const std::string& smoothness, const py::list& constraints, const EditingOptions& editing,
                     const LengthSolver& solver, const std::string& solver_type, Backend backend) {
  const CurveComponents& cc = curve_components();
  CurveTerms t;
  std::vector<std::string> smooth = cc.energies.names();
  smooth.erase(std::remove(smooth.begin(), smooth.end(), "attractor_distance"), smooth.end());
  if (std::find(smooth.begin(), smooth.end(), smoothness) == smooth.end()) {
    std::string v;
    for (const auto& s : smooth) v += (v.empty() ? "" : ", ") + s;
    throw InvalidConfig("smoothness '" + smoothness + "': expected one of " + v);
  }
  Config none;
  t.smoothness = cc.energies.create(smoothness, backend, none);
  bool lengths = false;
  int totals = 0;
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    const std::string where = "constraints[" + std::to_string(i) + "]";
    if (!py::isinstance<py::dict>(constraints[i])) throw InvalidConfig(where + ": expected a dict {'type': name, ...}");
    Config k = to_config(constraints[i].cast<py::dict>(), where);
    const std::string type = k.get_choice("type", "segment_lengths", cc.constraints.names(), "constraint kind");
    t.constraints.push_back(cc.constraints.create(type, backend, k));
    k.check_no_unknown_keys();
    lengths |= type == "segment_lengths";
    if (type == "total_length") ++totals;
    if ((type == "total_length" || type == "tangent") && editing.solve_region == SolveRegion::Support)
      throw InvalidConfig(where + ": " + type + " constraints are not solved on the edit's support; "
                          "give solve_region='curve'");
  }
  if (totals > 1) throw InvalidConfig("constraints: a second total_length; keep one");
  if (lengths && totals)
    throw InvalidConfig("constraints: total_length and segment_lengths together: the total is the sum of the segments; keep one");
  if (!lengths && !totals)
    throw InvalidConfig("constraints: lengths are what this editor preserves; include {'type': 'segment_lengths'} or "
                        "{'type': 'total_length'} (length='segment_lengths' or 'total_length')");
  if (totals && !solver.takes_dense_rows()) {
    std::string takers;
    for (const auto& name : cc.solvers.names())
      if (cc.solvers.create(name, Backend::Optimized, none)->takes_dense_rows()) takers += (takers.empty() ? "" : ", ") + name;
    throw InvalidConfig("solver '" + solver_type + "' does not take the total_length constraint; the solvers that do: " + takers);
  }
  t.total = totals > 0;
  return t;
}

py::dict edit_curve(const Eigen::Ref<const Eigen::MatrixXd>& points, bool closed, int levels, int level, int wrinkle_level,
                    const std::vector<int>& indices, const Eigen::Ref<const Eigen::MatrixXd>& offsets,
                    const std::vector<double>& chord_scales, int drag_steps, const std::string& smoothness, double beta,
                    const py::list& constraints, const std::string& solver_type, const py::dict& solver_options,
                    const std::string& explicit_step, const std::string& details, const std::string& solve_region,
                    const std::string& implementation) {
  const Backend backend = backend_arg(implementation);
  const Polyline curve = polyline_arg(points, closed);
  const int L = levels_arg(curve, levels);
  if (level < 0 || level > L)
    throw InvalidIndex("edit_curve: level " + std::to_string(level) + " is outside the hierarchy (levels 0.." + std::to_string(L) + ")");
  if (wrinkle_level != -1 && (wrinkle_level < level || wrinkle_level >= L))
    throw InvalidInput("edit_curve: wrinkle_level " + std::to_string(wrinkle_level) + " must lie in [level, levels-1] = [" +
                       std::to_string(level) + ", " + std::to_string(L - 1) + "] or be -1");
  if (!(beta >= 0 && beta <= 1)) throw InvalidConfig("beta: " + std::to_string(beta) + " is not in [0, 1]");
  if (drag_steps < 1) throw InvalidConfig("drag_steps: at least 1");
  const int segments = (closed ? curve.n_points() : curve.n_points() - 1) >> (L - level);
  const int m = closed ? segments : segments + 1;
  if (offsets.rows() != static_cast<Eigen::Index>(indices.size()) || (offsets.cols() != 2 && offsets.cols() != 3))
    throw InvalidInput("edit_curve: offsets must be k×2 or k×3 for k = " + std::to_string(indices.size()) + " indices, got " +
                       std::to_string(offsets.rows()) + "×" + std::to_string(offsets.cols()));
  if (chord_scales.size() != indices.size()) throw InvalidInput("edit_curve: one chord scale per index (0: use the offset)");
  finite_arg(offsets, "edit_curve: offsets");
  finite_arg(beta, "edit_curve: beta");
  for (std::size_t i = 0; i < chord_scales.size(); ++i) finite_arg(chord_scales[i], "edit_curve: chord_scales[" + std::to_string(i) + "]");
  CurveEdit e;
  e.edit_level = level;
  e.wrinkle_level = wrinkle_level;
  e.options = editing_arg(explicit_step, details, solve_region);
  for (std::size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] >= m || indices[i] < -m)
      throw InvalidIndex("edit_curve: index " + std::to_string(indices[i]) + " is not on the level-" + std::to_string(level) +
                         " polygon of " + std::to_string(m) + " points");
    if (!(chord_scales[i] >= 0)) throw InvalidInput("edit_curve: chord scales must be ≥ 0");
    CurveMove mv;
    mv.index = indices[i];
    mv.chord_scale = chord_scales[i];
    for (Eigen::Index c = 0; c < offsets.cols(); ++c) mv.offset[static_cast<int>(c)] = offsets(static_cast<Eigen::Index>(i), c);
    e.moves.push_back(mv);
  }
  const std::unique_ptr<LengthSolver> solver = solver_arg(solver_type, solver_options, backend);
  const CurveTerms terms = terms_arg(smoothness, constraints, e.options, *solver, solver_type, backend);
  CurveObjective objective;
  objective.smoothness = terms.smoothness.get();
  objective.beta = beta;
  for (const auto& k : terms.constraints) objective.constraints.push_back(k.get());

  EditStages first, last;
  int solves = 0, outer = 0, done = 0;
  double explicit_s = 0, solve_s = 0, time_s = 0;
  std::string message;
  Termination termination = Termination::Converged;
  Polyline current = curve;
  {
    py::gil_scoped_release release;
    for (const CurveEdit& step : fairshape::drag_steps(e, drag_steps)) {
      last = run_editing_loop(current, L, step, objective, *solver, backend, &curve);
      if (done == 0) first = last;
      ++done;
      solves += last.solve.solves;
      outer += last.solve.outer_iterations;
      explicit_s += last.explicit_s;
      solve_s += last.solve_s;
      time_s += last.total_s;
      current.points = last.final;
      message = last.solve.summary.message;
      if (!last.solve.converged()) {
        termination = last.solve.summary.termination;
        if (drag_steps > 1) message = "drag step " + std::to_string(done) + ": " + message;
        break;
      }
    }
  }
  const std::string outcome = std::string(to_string(termination)) + ": " + message;
  for (const auto* stage : {&first.reference, &last.edited, &last.attracting, &current.points})
    finite_result(*stage, "edit_curve: a stage of the edit (" + outcome + ")");
  const Eigen::VectorXd original = segment_lengths(curve.points, closed);
  const CurveMetrics metrics = measure_curve(current.points, closed, original, last.attracting);
  const Eigen::VectorXd l = segment_lengths(current.points, closed);
  py::dict out;
  out["levels"] = L;
  out["termination"] = std::string(to_string(termination));
  out["succeeded"] = termination == Termination::Converged;
  out["iterations"] = solves;
  out["residual"] = last.solve.length_error;
  out["message"] = message;
  out["solves"] = solves;
  out["outer_iterations"] = outer;
  out["drag_steps_done"] = done;
  out["length_error"] = last.solve.length_error;
  out["length_error_max"] = metrics.length_error_max;
  out["length_error_rms"] = metrics.length_error_rms;
  out["total_length_change"] = metrics.total_length_change;
  out["bending_energy"] = metrics.bending_energy;
  out["distance_to_attractor"] = metrics.distance_to_attractor;
  out["wrinkles"] = metrics.wrinkles;
  out["length_constraint"] = std::string(last.length_mode == LengthMode::Total ? "total_length" : "segment_lengths");
  out["total_length_asked"] = last.total_length_asked;
  out["total_length_error"] = std::abs(l.sum() - last.total_length_asked) / last.total_length_asked;
  out["stationarity"] = last.solve.history.empty() ? py::object(py::none()) : py::cast(last.solve.history.back().stationarity);
  out["min_reduced_hessian_eig"] =
      std::isnan(last.solve.min_reduced_hessian_eig) ? py::object(py::none()) : py::cast(last.solve.min_reduced_hessian_eig);
  out["saddle_escapes"] = last.solve.saddle_escapes;
  out["explicit_pull_back"] = last.explicit_step.worst_pull_back;
  out["explicit_unreachable_chains"] = last.explicit_step.unreachable_chains;
  out["explicit_s"] = explicit_s;
  out["solve_s"] = solve_s;
  out["time_s"] = time_s;
  out["moved_points"] = last.moved_points;
  out["reference"] = py::cast(std::move(first.reference));
  out["edited"] = py::cast(std::move(last.edited));
  out["attracting"] = py::cast(std::move(last.attracting));
  out["final"] = py::cast(std::move(current.points));
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
  m.def("_edit_curve", &edit_curve, py::arg("points"), py::arg("closed"), py::arg("levels"), py::arg("level"),
        py::arg("wrinkle_level"), py::arg("indices"), py::arg("offsets"), py::arg("chord_scales"), py::arg("drag_steps"),
        py::arg("smoothness"), py::arg("beta"), py::arg("constraints"), py::arg("solver"), py::arg("solver_options"),
        py::arg("explicit_step"), py::arg("details"), py::arg("solve_region"), py::arg("implementation"),
        "The curve edit's C++ half; call fairshape.edit_curve().");
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
