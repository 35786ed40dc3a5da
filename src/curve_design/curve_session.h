// A designer's session with the curve editor of Sauvage, Hahmann and Bonneau, "Length
// preserving multiresolution editing of curves": a curve and its multiresolution hierarchy, the
// §3 objective and length solver, and edits applied one editing loop (§4.1) at a time, each
// from the curve the previous one left, every one keeping the lengths of the curve the session
// started from. Every step measures its own result (lengths against the original curve, the
// plane of a planar curve, new self-crossings, how much of a drag its handles kept) and says in
// its summary when the result misses what was asked (papers/sauvage/README.md, "Step by step:
// the session"). The command line's curve runs, Python's fairshape.CurveSession and the
// interactive editor drive this one loop.
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "fairshape/core/summary.h"
#include "fairshape/curve_design/curve_metrics.h"
#include "fairshape/curve_design/editing_loop.h"

namespace fairshape {

//! What every step of a session shares: the §3 objective's terms, the length solver, how the
//! loop keeps an edit local, and whether an edit that is not honoured fails its step.
struct CurveEditSettings {
  EditingOptions editing;  // applied to every step (a CurveEdit's own `options` are replaced)
  //! false (a config's editing.partial_edit: fail): an edit whose handles were pulled back or
  //! returned ends edit_undone, one whose attracting curve keeps wrong lengths constraints_unmet;
  //! true: such a step stays converged, its message saying what happened.
  bool accept_partial_edit = false;
  double beta = 0.5;  // eq. 2: (1−β)·smoothness + β·distance to C_A
  std::unique_ptr<CurveEnergy> smoothness;
  std::vector<std::unique_ptr<CurveConstraintKind>> constraints;
  std::unique_ptr<LengthSolver> solver;
  Backend backend = Backend::Optimized;

  CurveObjective objective() const;
};

//! What a step measured on its result.
struct CurveStepChecks {
  CurveMetrics metrics;  // C_F against the original curve's segment lengths and this step's C_A
  double total_length_error = 0;                  // |L(C_F) − the total the solve aimed at| / that total
  double segment_stretch_min = 1, segment_stretch_max = 1;  // C_F's segment lengths over the original's
  double attractor_length_error = 0;              // C_A's max relative segment-length change from C_R
  //! The fraction of the points outside the edit's support that moved (to rounding), in C_F and C_A.
  double moved_outside_support = 0, attractor_moved_outside_support = 0;
  //! At a drag's last step: the share of the whole drag's displacement its handles kept
  //! (curve_metrics.h handle_reach), and how far the handles' asked places over-stretch the
  //! curve (segment lengths only; −1: not measured). Earlier steps: 1 and −1.
  double handle_reach = 1, overstretch = -1;
  //! A planar original curve: the current curve's distance from its plane, and whether a step
  //! solved in the plane left it (a failed check); NaN and false for a space curve.
  double out_of_plane = std::numeric_limits<double>::quiet_NaN();
  bool left_plane = false;
  //! A planar original curve: the current curve's self-crossings, and those the original had
  //! (crossings the edits made fold the curve); −1 for a space curve.
  int self_crossings = -1, original_self_crossings = -1;
};

//! One editing loop's outcome.
struct CurveStep {
  int index = 0;                       // 0, 1, ... in the session's order
  int drag_step = 1, drag_steps = 1;   // its place in a drag
  //! C_R, C_D, C_A and C_F, the explicit step's report and the solve's (history, second-order
  //! verdict per the solver's second_order option, min_reduced_hessian_eig).
  EditStages stages;
  CurveStepChecks checks;
  //! The solve's summary, then the checks': edit_undone (handles pulled back or returned),
  //! constraints_unmet (attracting-curve lengths the explicit step could not place, a planar
  //! curve that left its plane), folded (new self-crossings); the message says why; residual:
  //! the solve's relative length error.
  SolveSummary summary;
  //! Notes for the message (each "edit k: ...; " or empty): the explicit step pulled handles
  //! back or left stretched chains; the edit was not honoured; the attracting curve's lengths
  //! are wrong.
  std::string explicit_note, undone_note, unmet_note;
  double solve_s = 0;  // the editing loop (its explicit step and solve; the solver's second-order check included)
  double check_s = 0;  // the session's checks above
  const MatrixX3& curve() const { return stages.final; }
  bool succeeded() const { return is_success(summary.termination); }
};

//! The steps so far, added up as a run reports them.
struct CurveSessionTotals {
  int steps = 0, solves = 0, outer_iterations = 0;
  double time_s = 0, explicit_s = 0, solve_s = 0, check_s = 0;  // time_s: the editing loops'
  double moved_outside_support = 0, attractor_moved_outside_support = 0;  // the worst step's
  double handle_reach = 1, explicit_length_error = 0;                     // the worst step's
  int unplaceable_midpoints = 0;
  bool every_step_in_plane = true;
  std::string explicit_notes, undone_note, unmet_note;  // every step's explicit note; the first others
  //! The first step whose solve did not converge (its summary prefixed "edit k: "); a run stops there.
  bool failed = false;
  SolveSummary failure;
};

class CurveSession {
 public:
  //! \throw InvalidInput unless `levels` is in 0..max_polyline_levels(curve) and every setting is given.
  CurveSession(Polyline curve, int levels, CurveEditSettings settings);
  CurveSession(const CurveSession&) = delete;
  CurveSession& operator=(const CurveSession&) = delete;
  CurveSession(CurveSession&&) = default;
  CurveSession& operator=(CurveSession&&) = default;

  //! One editing loop of §4.1 on the current curve. `e.drag_step` of `e.drag_steps` places it in
  //! a drag (1 of 1: an edit of its own): its first step starts the drag, its last judges how
  //! much of the whole drag the handles kept. Never throws for the numerics (the summary says).
  //! \throw InvalidInput as run_editing_loop (a level or control point off the hierarchy, an
  //! infeasible edit, zero-length segments); the session is then unchanged.
  CurveStep edit(const CurveEdit& e);
  //! The next of the `steps` equal shares of `whole` (drag_steps in editing_loop.h): the first
  //! call starts the drag, the `steps`-th ends it. \throw InvalidInput when another drag is
  //! unfinished, or as edit().
  CurveStep drag_step(const CurveEdit& whole, int steps);

  const Polyline& current() const { return current_; }
  const Polyline& original() const { return original_; }
  //! The original curve's plane (planar false for a space curve): the plane checks' reference.
  const CurvePlane& original_plane() const { return original_plane_; }
  int levels() const { return levels_; }
  //! Control points of level `level` (0 = coarsest .. levels()). \throw InvalidInput off the hierarchy.
  int control_points(int level) const;
  const CurveEditSettings& settings() const { return settings_; }
  const CurveSessionTotals& totals() const { return totals_; }
  //! The last step (nullptr before the first).
  const CurveStep* last() const { return steps_ ? &last_ : nullptr; }
  //! The session's verdict so far, as a run reports it: the first failed solve, else the last
  //! solve's (named "edit k: " when there were several steps); then every step's notes and the
  //! current curve's checks, as a step's summary.
  SolveSummary outcome() const;

 private:
  Polyline original_, current_;
  int levels_ = 0;
  CurveEditSettings settings_;
  Eigen::VectorXd original_lengths_;
  CurvePlane original_plane_;
  int original_crossings_ = -1;
  // The drag under way: where its handles were before its first step, the displacements its
  // steps asked for so far, and (drag_step) the whole move and the next share.
  MatrixX3 drag_start_, drag_asked_;
  CurveEdit drag_whole_;
  int drag_next_ = 0, drag_total_ = 0;
  CurveStep last_;
  int steps_ = 0;
  CurveSessionTotals totals_;
};

}  // namespace fairshape
