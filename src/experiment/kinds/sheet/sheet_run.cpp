// The sheet run kind's execution: the config's steps through a SheetSession (sheet_steps.h),
// each step's results turned into rows (steps.csv, cells.csv, the runs row) and files.
#include "fairshape/experiment/kinds/sheet/sheet_run.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "fairshape/core/memory.h"
#include "fairshape/core/summary.h"
#include "fairshape/core/timer.h"
#include "fairshape/experiment/kinds/sheet/free_curves.h"
#include "fairshape/experiment/kinds/sheet/sheet_files.h"
#include "fairshape/experiment/kinds/sheet/sheet_steps.h"
#include "fairshape/experiment/metric_format.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/io/vtk_io.h"
#include "fairshape/mesh/disjoint_union.h"
#include "fairshape/mesh/polyline.h"
#include "fairshape/mesh/surface_mesh.h"

namespace fairshape {
namespace fs = std::filesystem;

const std::vector<std::string>& sheet_metric_columns() {
  static const std::vector<std::string> cols{
      "sheets", "steps", "dofs", "levels", "constraint_rows", "dropped_rows", "constraint_residual", "max_constraint_error",
      "energy", "spans_refined", "refinement_rounds", "objective_error_estimate", "surface_change_estimate",
      "condition_estimate", "analyze_s", "solve_s", "time_s", "peak_rss_mb", "unused_keys", "termination", "message"};
  return cols;
}

const std::vector<std::string>& sheet_cell_columns() {
  static const std::vector<std::string> cols{"sheet", "when", "round", "level", "u0", "v0", "size_u", "size_v", "error"};
  return cols;
}

const std::vector<std::string>& sheet_step_columns() {
  static const std::vector<std::string> cols{"step", "sheet", "dofs", "levels", "constraint_rows", "dropped_rows",
                                             "constraint_residual", "max_constraint_error", "energy", "spans_refined",
                                             "refinement_rounds", "analyze_s", "solve_s", "factorization", "curve_error",
                                             "curve_alone_error", "curve_error_refined", "curve_error_limit"};
  return cols;
}

namespace {

// The sheets at their current shape as one mesh (separate components) with displacement_norm.
SurfaceMesh sheets_mesh(const SheetSession& session, const std::vector<bspline::VariationalSheet>& sheets, int per_span) {
  std::vector<SurfaceMesh> meshes;
  for (std::size_t k = 0; k < sheets.size(); ++k)
    meshes.push_back(bspline::tessellate(sheets[k].surface(), sheets[k].coefficients(), per_span, session.initial_surface(k),
                                         session.initial_coefficients(k)));
  return disjoint_union(meshes);
}

// What the runs row adds up over the steps.
struct RunTotals {
  double analyze_s = 0, solve_s = 0, energy = 0, residual = 0, max_err = 0, cond = 0;
  int dofs = 0, rows = 0, dropped = 0, refined = 0, rounds = 0;
  bool solved_any = false;  // a sheet or a free curve had something acting on it
  bool failed = false;
  // Per sheet, the last step's constraint error per leaf cell after every solve (Figure 3).
  std::vector<std::vector<std::vector<bspline::CellError>>> cell_errors;
};

MetricRow start_row(const SheetRunSpec& spec) {
  MetricRow row;
  for (const auto& c : sheet_metric_columns()) row[c] = "";
  row["implementation"] = std::string(to_string(spec.implementation));
  row["unused_keys"] = spec.unused_keys_cell();
  row["solver.type"] = spec.solver_type;
  row["sheets"] = std::to_string(spec.sheets.size());
  row["steps"] = std::to_string(spec.steps());
  row["termination"] = std::string(to_string(Termination::Converged));
  return row;
}

std::vector<std::string> sheet_step_row(int step, const std::string& name, const bspline::VariationalSheet& sheet, const SheetSolve& s) {
  const bspline::DesignReport& r = s.report;
  const auto& surface = sheet.surface();
  return {std::to_string(step), name, std::to_string(surface.dof_count()), std::to_string(surface.level_count()),
          std::to_string(r.constraint_rows), std::to_string(r.qp.dropped_rows), num(r.qp.constraint_residual),
          num(r.max_constraint_error), num(r.energy), std::to_string(r.spans_refined), std::to_string(r.rounds),
          num(r.analyze_s), num(r.solve_s), s.factorization, num(r.curve_error), num(r.curve_alone_error),
          num(r.curve_error_refined), num(r.curve_error_limit)};
}

// One sheet's solve: its steps.csv row, the row's termination and message, the totals.
void record_sheet(const SheetConfigSteps& steps, const SheetConfigStep& st, const SheetSolve& s, const RunOutputs& out,
                  MetricRow& row, RunTotals& t) {
  const SheetRunSpec& spec = steps.spec();
  const std::string& name = spec.sheets[s.sheet].name;
  const bspline::DesignReport& r = s.report;
  out.add_row("steps", sheet_step_row(st.step, name, steps.session().sheet(s.sheet), s));
  const bool this_failed = !is_success(r.qp.summary.termination);
  if (this_failed && !t.failed) {  // the first failure names the row
    row["termination"] = std::string(to_string(r.qp.summary.termination));
    row["message"] = "step " + std::to_string(st.step) + ", sheet " + name + ": " + r.message;
  } else if (!t.failed && !r.message.empty()) {
    row["message"] = name + ": " + r.message;
  }
  if (spec.solver_type == "paper")  // a different answer, said where the numbers are
    row["message"] += std::string(row["message"].empty() ? "" : "; ") +
                      "paper split: the constrained control points are the minimum-norm least-squares solution of "
                      "their rows, not optimized (energy above the minimizer's)";
  t.failed = t.failed || this_failed;
  t.cell_errors[s.sheet] = r.errors_per_round;  // the last step's solve wins (Figure 3: every refinement round)
  t.analyze_s += r.analyze_s;
  t.solve_s += r.solve_s;
  t.refined += r.spans_refined;
  t.rounds += r.rounds;
  t.solved_any = true;
  if (st.step + 1 == spec.steps() || t.failed) {  // the row: the last step, or the one that failed
    t.energy += r.energy;
    t.residual = std::hypot(t.residual, r.qp.constraint_residual);
    t.max_err = std::max(t.max_err, r.max_constraint_error);
    t.rows += static_cast<int>(r.constraint_rows);
    t.dropped += r.qp.dropped_rows;
    if (!std::isnan(r.qp.condition_estimate)) t.cond = std::max(t.cond, r.qp.condition_estimate);
  }
}

// A free curve's row (its group's termination), the row's termination and message, the totals.
void record_free_curve(const SheetConfigSteps& steps, int step, const FreeCurveStep& c, const RunOutputs& out, MetricRow& row,
                       RunTotals& t) {
  t.solved_any = true;
  out.add_row("steps", free_curve_step_row(step, c));
  if (!t.failed && !is_success(c.termination)) {
    t.failed = true;
    row["termination"] = std::string(to_string(c.termination));
    row["message"] = "step " + std::to_string(step) + ", curve " + c.name + ": " + c.message;
  }
  if (step + 1 == steps.spec().steps() || t.failed) {
    t.energy += c.energy;
    t.residual = std::hypot(t.residual, c.residual);
    t.max_err = std::max(t.max_err, c.max_error);
    t.dofs += c.dofs;
    t.rows += c.rows;
  }
}

// Per step: all sheets in one polydata (point array displacement_norm) and the space curves
// (a failed step's too: what it achieved, under its termination).
void write_step_files(const SheetConfigSteps& steps, const SheetConfigStep& st, bool failed, const RunOutputs& out) {
  const SheetRunSpec& spec = steps.spec();
  const SheetSession& session = steps.session();
  const bool last = st.step + 1 == spec.steps() || failed;
  if (spec.vtk == VtkPolicy::All || (spec.vtk == VtkPolicy::Final && last)) {
    const std::string stem = (fs::path(out.dir) / "vtk" / (out.run_id + "_step" + std::to_string(st.step))).string();
    write_vtp(sheets_mesh(session, session.sheets(), spec.samples_per_span), stem + ".vtp");
    st.overlay.write(stem + "_constraints.vtp");
    // The step's first solve, before automatic refinement changed it (no "_step" in the name:
    // figure scripts glob the steps).
    const bool refined = std::any_of(st.result.sheets.begin(), st.result.sheets.end(),
                                     [](const SheetSolve& s) { return s.report.unrefined != nullptr; });
    if (refined) {
      std::vector<bspline::VariationalSheet> first = session.sheets();
      for (const SheetSolve& s : st.result.sheets)
        if (s.report.unrefined) first[s.sheet] = *s.report.unrefined;
      const std::string before = (fs::path(out.dir) / "vtk" / (out.run_id + "_unrefined" + std::to_string(st.step))).string();
      write_vtp(sheets_mesh(session, first, spec.samples_per_span), before + ".vtp");
      st.overlay.write(before + "_constraints.vtp");
    }
  }
  if (spec.vtk == VtkPolicy::All) write_sheet_files(out, spec.sheets, session.sheets(), st.step);
  fs::create_directories(fs::path(out.dir) / "curves");
  for (const auto& [name, pts] : st.curves_now) {
    MatrixX3 X(static_cast<Eigen::Index>(pts.size()), 3);
    for (std::size_t i = 0; i < pts.size(); ++i) X.row(static_cast<Eigen::Index>(i)) = pts[i].transpose();
    write_polyline(Polyline{X, false}, (fs::path(out.dir) / "curves" /
                                        (out.run_id + "_step" + std::to_string(st.step) + "_" + file_name_part(name) + ".obj"))
                                           .string());
  }
}

// §4.4's a-posteriori estimate after the last step (refinement.estimate_objective_error).
void estimate_objective_error(SheetConfigSteps& steps, MetricRow& row) {
  double energy_change = 0, surface_change = 0;
  SheetSession& session = steps.session();
  for (std::size_t k = 0; k < session.sheets().size(); ++k) {
    if (session.active(k).empty()) continue;
    const bspline::ObjectiveErrorEstimate e = session.estimate_objective_error(k);
    if (!e.message.empty()) row["message"] = e.message;
    energy_change = std::max(energy_change, e.energy_change);
    surface_change = std::max(surface_change, e.surface_change);
  }
  row["objective_error_estimate"] = num(energy_change);
  row["surface_change_estimate"] = num(surface_change);
}

// Constraint error per leaf cell after every solve of the last step (Figure 3): `when` is
// before (the first solve), after (the last; a single solve is both) or between.
void write_cells(const SheetRunSpec& spec, const RunTotals& t, const RunOutputs& out) {
  for (std::size_t k = 0; k < t.cell_errors.size(); ++k)
    for (std::size_t n = 0; n < t.cell_errors[k].size(); ++n) {
      std::vector<std::string> whens;
      if (n == 0) whens.push_back("before");
      if (n + 1 == t.cell_errors[k].size()) whens.push_back("after");
      if (whens.empty()) whens.push_back("between");
      for (const std::string& when : whens)
        for (const bspline::CellError& e : t.cell_errors[k][n]) {
          const Eigen::Vector2d h = std::ldexp(1.0, -e.cell.level) * spec.sheets[k].shape.span_size;  // design units
          out.add_row("cells", {spec.sheets[k].name, when, std::to_string(n + 1), std::to_string(e.cell.level), num(e.cell.i * h.x()),
                                num(e.cell.j * h.y()), num(h.x()), num(h.y()), num(e.error)});
        }
    }
}

// The runs row's totals; every sheet's unknowns and layers, whether or not something acted on it.
void finish_row(const SheetSession& session, RunTotals& t, MetricRow& row) {
  int levels = 0;
  for (const bspline::VariationalSheet& sh : session.sheets())
    t.dofs += sh.surface().dof_count(), levels = std::max(levels, sh.surface().level_count());
  if (!t.solved_any && !t.failed && row["message"].empty())
    row["message"] = "no constraint acts on any sheet at any step: nothing was solved (the sheets keep their shapes)";
  row["dofs"] = std::to_string(t.dofs);
  row["levels"] = std::to_string(levels);
  row["constraint_rows"] = std::to_string(t.rows);
  row["dropped_rows"] = std::to_string(t.dropped);
  row["constraint_residual"] = num(t.residual);
  row["max_constraint_error"] = num(t.max_err);
  row["energy"] = num(t.energy);
  row["spans_refined"] = std::to_string(t.refined);
  row["refinement_rounds"] = std::to_string(t.rounds);
  if (t.cond > 0) row["condition_estimate"] = num(t.cond);
  row["analyze_s"] = num(t.analyze_s);
  row["solve_s"] = num(t.solve_s);
}

// Every step through the session, then the run's own outputs.
void run_steps(SheetConfigSteps& steps, const RunOutputs& out, MetricRow& row, int& step) {
  RunTotals t;
  t.cell_errors.resize(steps.spec().sheets.size());
  while (steps.next_step() < steps.steps() && !t.failed) {
    step = steps.next_step();
    const SheetConfigStep st = steps.advance();
    for (const SheetSolve& s : st.result.sheets) record_sheet(steps, st, s, out, row, t);
    for (const FreeCurveStep& c : st.free_curves) record_free_curve(steps, st.step, c, out, row, t);
    write_step_files(steps, st, t.failed, out);
  }
  if (steps.spec().estimate_objective_error && row["termination"] == to_string(Termination::Converged))
    estimate_objective_error(steps, row);
  write_cells(steps.spec(), t, out);
  const SheetSession& session = steps.session();
  write_mesh(sheets_mesh(session, session.sheets(), steps.spec().samples_per_span), out.final_path());
  write_sheet_files(out, steps.spec().sheets, session.sheets(), -1);
  finish_row(session, t, row);
}

}  // namespace

MetricRow execute_sheet_run(SheetRunSpec& spec, const RunOutputs& out) {
  MetricRow row = start_row(spec);
  const Timer wall;
  reset_peak_rss();  // this run's own peak, not an earlier run's of the sweep
  int step = 0;
  try {
    SheetConfigSteps steps(std::move(spec));
    run_steps(steps, out, row, step);
  } catch (const OutputError& e) {  // results incomplete: not a finished run
    row["termination"] = std::string(to_string(Termination::OutputFailed));
    row["message"] = e.what();
  } catch (const Error& e) {
    row["termination"] = std::string(to_string(Termination::InvalidInput));
    row["message"] = "step " + std::to_string(step) + ": " + e.what();
  }
  row["time_s"] = num(wall.seconds());
  row["peak_rss_mb"] = num(peak_rss_mb());
  return row;
}

}  // namespace fairshape
