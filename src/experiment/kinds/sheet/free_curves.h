// Variational curves in sheet configs: a `curves:` entry with
// `variational: {spans, degree, alpha, beta}` is a free curve (bspline/variational_curve.h)
// that starts as the least-squares fit of its form and then moves by its own constraints —
// `constraints:` entries of type curve_point (`curve, t, target | by, moves`) and curve_tangent
// (`curve, t, target`) — and with every sheet a curve constraint joins to it. At each step the
// sheets and free curves joined by the active constraints are solved as one program
// (bspline/joined_design.h); the other sheets as before.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "fairshape/bspline/joined_design.h"
#include "fairshape/core/config.h"
#include "fairshape/experiment/kinds/sheet/sheet_run.h"
#include "fairshape/io/constraint_overlay.h"

namespace fairshape {

//! A curve entry's `variational:` block (absent: a fixed curve). \throw InvalidConfig naming
//! the key: weights both 0, `edits` on a variational curve, a closed one.
void read_variational(Config& c, SpaceCurveSpec& s);

//! Whether a `constraints:` entry is a variational curve's own (type curve_point / curve_tangent).
bool is_curve_constraint(const Config& c);
const std::vector<std::string>& curve_constraint_types();
//! \throw InvalidConfig naming the key (t outside [0, 1], target and by both given, ...).
CurveConstraintSpec read_curve_constraint(Config& c, const std::string& label);

//! Whether a `constraints:` entry is of type tangent_continuity.
bool is_tangent_continuity(const Config& c);
//! `{type: tangent_continuity, curve, sheets: [a, b], keep: [left|right, left|right]}`.
//! \throw InvalidConfig naming the key.
TangentContinuitySpec read_tangent_continuity(Config& c, const std::string& label);

//! After the whole config is read: curve constraints name variational curves, joints use the
//! mortar rows, joined sheets have no normal constraint, a tangent_continuity names a variational
//! curve and two sheets each joined to it once, no objective-error estimate with free
//! curves (automatic refinement refines sheets and curves together: bspline/joined_design.h).
//! Marks the joints (SheetConstraintSpec::joins_free_curve). \throw InvalidConfig naming the key.
void check_free_curves(SheetRunSpec& s);

//! What a step's joint solves give a joined sheet: its report (the joint's termination and
//! message; analyze_s, solve_s and dropped_rows in its group's first sheet only; constraint_rows:
//! the rows acting on it, its own and its joints').
struct JoinedSheetStep {
  bspline::DesignReport report;
  std::string factorization;  // how the group's program was factored (qp::factorization_note)
};
//! A free curve after a step (its steps.csv row).
struct FreeCurveStep {
  std::string name;
  int dofs = 0, rows = 0, levels = 1, spans_refined = 0, rounds = 1;
  double residual = 0, max_error = 0, energy = 0;
  Termination termination = Termination::Converged;
  std::string message, factorization;
};
struct JoinedStep {
  std::map<std::size_t, JoinedSheetStep> sheets;  // by sheet index: the sheets solved jointly
  std::vector<FreeCurveStep> curves;              // the free curves solved at this step
};

//! steps.csv's row of a free curve (sheet column `curve:<name>`; levels, spans_refined and
//! refinement_rounds its own).
std::vector<std::string> free_curve_step_row(int step, const FreeCurveStep& c);

class FreeCurves {
 public:
  //! Fits every variational curve to its initial polyline. \throw InvalidInput for one that
  //! cannot be fitted (zero length).
  FreeCurves(const SheetRunSpec& spec, const std::map<std::string, std::vector<Vec3>>& initial_polylines);
  //! Solves the step's joined groups, sets the joined sheets' coefficients and the free
  //! curves' control points, puts every free curve's shape into `curves_now` (sampled) and
  //! its curve and point targets into `overlay`. `own[k]`: sheet k's active constraints
  //! without its joints; `solver`: the session's (bspline/sheet_session.h).
  JoinedStep solve_step(const SheetRunSpec& spec, int step, qp::QpSolver& solver, std::vector<bspline::VariationalSheet>& sheets,
                        const std::vector<bspline::SheetEnergy>& energies, const std::vector<std::vector<bspline::SheetConstraint>>& own,
                        std::map<std::string, std::vector<Vec3>>& curves_now, ConstraintOverlay& overlay);

 private:
  std::vector<std::size_t> spec_index_;  // the spec.curves entry of each free curve
  std::vector<bspline::VariationalCurve> curves_, initial_;
};

}  // namespace fairshape
