// Variational sheet experiments (configs/welch-witkin): hierarchical B-spline sheets, space
// curves shared between them, constraints that switch on at design steps (a push-pin at step
// 0, a curve edited at step 2, ...), a constrained solver and automatic refinement. A config
// is a sheet run when it has `sheets:`.
#pragma once

#include <memory>
#include <array>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "fairshape/bspline/sheet_geometry.h"
#include "fairshape/bspline/uniform_basis.h"
#include "fairshape/bspline/variational_curve.h"
#include "fairshape/bspline/variational_sheet.h"
#include "fairshape/experiment/run_outputs.h"
#include "fairshape/experiment/vtk_policy.h"
#include "fairshape/experiment/run_basics.h"
#include "fairshape/qp/qp_solver.h"

namespace fairshape {

struct SheetSpec {
  std::string name;
  bspline::SheetShape shape;
  bspline::SheetPlacement placement;
  std::vector<bspline::SpanId> refine;
  std::string file;  // non-empty: the sheet starts from this saved sheet (kinds/sheet/sheet_files.h)
  std::shared_ptr<const bspline::VariationalSheet> loaded;  // ... as read at load
};

struct SpaceCurveEdit {
  int step = 0;
  double t = 0.5, radius = 0.25;
  Vec3 by = Vec3::Zero();
};

struct SpaceCurveSpec {
  std::string name;
  std::string from_sheet;                 // non-empty: traced on this sheet ...
  //! ... as it is at the curve's first step (the first step a constraint uses it), after the
  //! steps before (`from_surface.surface: current`, the paper's promotion of a surface curve), or
  //! as it was before any step (`initial`). A curve traced on the current surface keeps that
  //! surface as its exact target (bspline::SurfaceTrace), so adding it moves nothing.
  bool trace_current = false;
  std::vector<Eigen::Vector2d> uv;        // ... along this uv curve (curve_forms.h), `samples` points
  std::vector<Vec3> points;               // or given as points, arc or bspline, sampled already
  int samples = 65;
  bool closed = false;                    // ends where it starts (edits wrap round)
  std::vector<SpaceCurveEdit> edits;
  //! A variational curve (`variational:`, kinds/sheet/free_curves.h): it starts as the
  //! least-squares fit of the form above and then moves by its own constraints (curve_point,
  //! curve_tangent) and with the sheets joined to it, solved together at every step.
  bool variational = false;
  bspline::CurveShape curve_shape;
  bspline::CurveEnergy curve_energy;
};

//! A point constraint's target moved by `by` from design step `step` on (moves add up).
struct PointMove {
  int step = 1;
  Vec3 by = Vec3::Zero();
};

struct SheetConstraintSpec {
  std::string sheet, curve, label;
  int step = 0;                 // active from this design step ...
  int until = -1;               // ... up to (not including) this one; −1: never removed
  bool relative = false;        // point: target is an offset from the initial surface point; offset: the initial offset
  //! Region and ribbon: the surface they hold (region: its positions, ribbon: its cross
  //! derivative), the initial sheet or the sheet as it is at the constraint's first step.
  enum class Held { None, Initial, Current } held = Held::None;
  std::vector<PointMove> moves;  // point: the target dragged over the steps
  bspline::SheetConstraint constraint;
  //! A curve constraint whose space curve is variational: a joint, solved with the curve.
  bool joins_free_curve = false;
  bool active_at(int s) const { return step <= s && (until < 0 || s < until); }
};

//! A variational curve's own constraint (type curve_point or curve_tangent).
struct CurveConstraintSpec {
  std::string curve, label;
  int step = 0, until = -1;
  bool relative = false;         // curve_point `by`: an offset from the initial curve's point
  std::vector<PointMove> moves;  // curve_point: the target dragged over the steps
  bspline::CurveConstraint constraint;
  bool active_at(int s) const { return step <= s && (until < 0 || s < until); }
};

//! Two sheets joined to one variational curve made tangent-continuous across it, while both
//! joints are active: the side of its joint's (u, v) curve each sheet keeps.
struct TangentContinuitySpec {
  std::string curve, label;
  std::array<std::string, 2> sheets;
  std::array<bool, 2> keep_left{true, false};
};

//! §5's session actions on a sheet's objective: install its current shape as the rest shape
//! (eq. 6 about it from then on), or melt the rest shape (back to eq. 4).
struct RestShapeAction {
  enum class Kind { Install, Melt } kind = Kind::Install;
  int step = 1;
  std::string sheet;  // empty: every sheet
};

struct SheetRunSpec : RunBasics {
  std::string solver_type;
  std::vector<SheetSpec> sheets;
  std::vector<SpaceCurveSpec> curves;
  std::vector<SheetConstraintSpec> constraints;
  std::vector<CurveConstraintSpec> curve_constraints;  // `constraints:` entries of a curve_* type
  std::vector<TangentContinuitySpec> tangent_continuity;  // type tangent_continuity (free_curves.h)
  std::vector<RestShapeAction> actions;
  bspline::SheetEnergy energy;
  bspline::RefinementOptions refinement;
  bool estimate_objective_error = false;
  //! The resolution probe of the curve constraints (bspline/curve_fidelity.h) after every step's
  //! solve, or only after the last step's (the design released; `refinement.curve_probe`).
  bool probe_every_step = false;
  std::unique_ptr<qp::QpSolver> solver;
  int samples_per_span = 6;
  VtkPolicy vtk = VtkPolicy::Final;  // vtk/<run>_step<k>.vtp: the last step, or every step
  int steps() const;

  //! \throw InvalidConfig naming the key (unknown sheets or curves, uv outside the domain, ...).
  //! \param search_dirs where relative sheet `file:` paths are looked up (input_search_dirs).
  //! Every key a run of this kind reads, with its default and doc (document_keys).
  static std::vector<OptionDoc> keys();
  static SheetRunSpec from_config(const YAML::Node& run_config, const std::vector<std::string>& search_dirs = {});
};

bool is_sheet_config(const YAML::Node& run_config);

//! The index of the sheet `name`. \throw InvalidConfig naming `key` and the sheets.
int sheet_config_index(const SheetRunSpec& s, const std::string& name, const std::string& key);
//! (u, v) points of `sheet` in design units: checked inside its domain (and, on a periodic
//! sheet, no segment half way round), converted to base spans. \throw InvalidConfig naming `what`.
void uv_to_spans(const SheetRunSpec& s, const std::string& sheet, std::vector<Eigen::Vector2d>& uv, const std::string& what);
//! A constraint on a sheet read from a `constraints:` entry (constraint_kinds.h), made ready for
//! the run: its sheet and space curve exist (a curve's (u, v) default: the curve's own trace),
//! its (u, v) in base spans. \throw InvalidConfig naming the key.
void prepare_sheet_constraint(const SheetRunSpec& s, SheetConstraintSpec& cs);
const std::vector<std::string>& sheet_metric_columns();  // runs.csv
const std::vector<std::string>& sheet_step_columns();    // steps.csv: one row per step and sheet
const std::vector<std::string>& sheet_cell_columns();    // cells.csv: constraint error per leaf cell

//! Runs every step, writes steps.csv rows (one per sheet, and one per variational curve with
//! `curve:<name>` in its sheet column), cells.csv (constraint error per leaf cell before and
//! after refinement), vtk/<run>_step<k>.vtp (every sheet, point array displacement_norm),
//! curves/<run>_step<k>_<curve>.obj, final.obj, and sheets/<run>_<sheet>.sheet (with
//! output.vtk: all also sheets/<run>_step<k>_<sheet>.sheet). Never throws
//! for problems of the input or the numerics: they become the row's termination and message.
MetricRow execute_sheet_run(SheetRunSpec& spec, const RunOutputs& out);

}  // namespace fairshape
