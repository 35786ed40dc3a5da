#include "fairshape/curve_design/curve_session.h"

#include <algorithm>
#include <cmath>

#include "fairshape/core/error.h"
#include "fairshape/core/message_format.h"
#include "fairshape/core/timer.h"
#include "fairshape/curve_design/curve_plane.h"
#include "fairshape/curve_design/edit_support.h"
#include "fairshape/curve_design/self_crossings.h"
#include "fairshape/curves/multires_polyline.h"

namespace fairshape {
namespace {

// Length preservation is explicit at level w + 1 (§4.1): lengths placed analytically, so
// anything above rounding is a length the step could not place.
constexpr double kExplicitLengthTolerance = 1e-9;

std::string edit_name(int k) { return "edit " + std::to_string(k) + ": "; }

bool same_move(const CurveMove& a, const CurveMove& b) {
  return a.index == b.index && a.offset == b.offset && a.chord_scale == b.chord_scale;
}

bool same_edit(const CurveEdit& a, const CurveEdit& b) {
  return a.edit_level == b.edit_level && a.wrinkle_level == b.wrinkle_level && a.moves.size() == b.moves.size() &&
         std::equal(a.moves.begin(), a.moves.end(), b.moves.begin(), same_move);
}

// What the explicit step could not do inside the edit's support (§4.1's step made local).
std::string explicit_note(int k, const EditStages& s) {
  const ExplicitLengthReport& x = s.explicit_step;
  std::string note;
  if (x.worst_pull_back > 0)
    note += edit_name(k) + "the edit asks for more length than the curve has inside its support: "
            "moved control point(s) pulled back by up to " + num(x.worst_pull_back) + " (" +
            num(100 * x.worst_pull_back / (rounding_tolerance(s.reference) * 1e12)) +
            " % of the curve's size) so the explicit step keeps the lengths locally; ";
  if (x.unreachable_chains > 0)
    note += edit_name(k) + "explicit step could not keep the lengths inside the support (" +
            std::to_string(x.unreachable_chains) + " level-e segment(s) stretched beyond their reference length, up to " +
            num(100 * x.worst_excess) + " % too long: left straight for the optimization); ";
  return note;
}

std::string undone_note(int k, const CurveEdit& e, const EditStages& s, const CurveStepChecks& c) {
  const double stretch = c.overstretch, r = c.handle_reach;
  if (!(s.explicit_step.worst_pull_back > 0 || s.explicit_step.unreachable_chains > 0 || r < kUndoneReach || stretch > 1e-9))
    return "";
  return "edit " + std::to_string(k) + " not honoured: " +
         (stretch > 1e-9 ? "it puts a handle " + num(100 * stretch) + " % farther from a control point than the curve "
                           "between them is long (over-stretched)"
          : r < kUndoneReach ? "the result kept " + num(100 * r) + " % of the handles' displacement" +
                                   (e.drag_steps > 1 ? " over the drag's " + std::to_string(e.drag_steps) + " steps" : "")
                             : std::string("the handles were pulled back so the lengths could be kept")) +
         " (editing.partial_edit: accept allows it); ";
}

std::string unmet_note(int k, const CurveEdit& e, const EditStages& s) {
  const ExplicitLengthReport& x = s.explicit_step;
  if (e.wrinkle_level < 0 || x.length_error <= kExplicitLengthTolerance) return "";
  return edit_name(k) + "the explicit step left the attracting curve's level-" + std::to_string(e.wrinkle_level + 1) +
         " lengths up to " + num(100 * x.length_error) + " % off (" + std::to_string(x.unplaceable_midpoints) +
         " midpoint(s) on chords shorter than the difference of their two lengths, " +
         std::to_string(x.unreachable_chains) + " chain(s) stretched beyond reach; editing.partial_edit: accept allows it); ";
}

// `s` judged by what the steps measured: notes first, then the current curve's plane and
// crossings. Each check changes only a converged outcome (the first failure is the one reported).
SolveSummary judged(SolveSummary s, const std::string& explicit_notes, const std::string& undone, const std::string& unmet,
                    bool accept_partial, const CurveStepChecks& c, const CurvePlane& plane) {
  const auto converged = [&] { return s.termination == Termination::Converged; };
  s.message = explicit_notes + s.message;
  if (converged() && !(undone + unmet).empty()) {
    if (!accept_partial) s.termination = undone.empty() ? Termination::ConstraintsUnmet : Termination::EditUndone;
    s.message = undone + unmet + s.message;
  }
  if (plane.planar && c.left_plane && converged()) {
    s.termination = Termination::ConstraintsUnmet;
    s.message = "the planar curve left its plane by " + num(c.out_of_plane) + " (" + num(c.out_of_plane / plane.size) +
                " of its size, tolerance " + num(kPlanarTolerance) + "); " + s.message;
  }
  if (plane.planar && c.self_crossings > c.original_self_crossings && converged()) {
    s.termination = Termination::Folded;
    s.message = "the result crosses itself: " + std::to_string(c.self_crossings - c.original_self_crossings) +
                " crossing(s) of segment pairs the input did not have; " + s.message;
  }
  return s;
}

}  // namespace

CurveObjective CurveEditSettings::objective() const {
  CurveObjective o;
  o.smoothness = smoothness.get();
  o.beta = beta;
  for (const auto& k : constraints) o.constraints.push_back(k.get());
  return o;
}

CurveSession::CurveSession(Polyline curve, int levels, CurveEditSettings settings)
    : original_(std::move(curve)), current_(original_), levels_(levels), settings_(std::move(settings)) {
  const int most = max_polyline_levels(original_.n_points(), original_.closed);
  if (levels_ < 0 || levels_ > most)
    throw InvalidInput("curve session: " + std::to_string(levels_) + " levels; a curve of " +
                       std::to_string(original_.n_points()) + " points allows 0.." + std::to_string(most));
  if (!settings_.smoothness || !settings_.solver)
    throw InvalidInput("curve session: a smoothness energy and a length solver are required");
  original_lengths_ = segment_lengths(original_.points, original_.closed);
  original_plane_ = fit_plane({&original_.points});
  if (original_plane_.planar) original_crossings_ = count_self_crossings(original_.points, original_.closed, original_plane_);
}

int CurveSession::control_points(int level) const {
  if (level < 0 || level > levels_)
    throw InvalidInput("curve session: level " + std::to_string(level) + " is outside the hierarchy (levels 0.." +
                       std::to_string(levels_) + ")");
  const int segments = (current_.closed ? current_.n_points() : current_.n_points() - 1) >> (levels_ - level);
  return current_.closed ? segments : segments + 1;
}

CurveStep CurveSession::drag_step(const CurveEdit& whole, int steps) {
  if (drag_total_ > 0 && (!same_edit(whole, drag_whole_) || steps != drag_total_))
    throw InvalidInput("curve session: a drag of " + std::to_string(drag_total_) + " steps is under way (" +
                       std::to_string(drag_next_ - 1) + " taken): take its remaining steps before another drag");
  if (steps < 1) throw InvalidInput("curve session: a drag takes at least 1 step, not " + std::to_string(steps));
  const int next = drag_total_ > 0 ? drag_next_ : 1;
  const CurveEdit share = drag_steps(whole, steps)[static_cast<std::size_t>(next - 1)];
  CurveStep step = edit(share);
  if (drag_total_ > 0) drag_whole_ = whole;
  return step;
}

CurveStep CurveSession::edit(const CurveEdit& e) {
  if (e.drag_steps < 1 || e.drag_step < 1 || e.drag_step > e.drag_steps)
    throw InvalidInput("curve session: drag step " + std::to_string(e.drag_step) + " of " + std::to_string(e.drag_steps));
  if (e.drag_step == 1 && drag_total_ > 0)
    throw InvalidInput("curve session: a drag of " + std::to_string(drag_total_) + " steps is under way (" +
                       std::to_string(drag_next_ - 1) + " taken): take its remaining steps first");
  if (e.drag_step > 1 && (e.drag_step != drag_next_ || e.drag_steps != drag_total_))
    throw InvalidInput("curve session: drag step " + std::to_string(e.drag_step) + " of " + std::to_string(e.drag_steps) +
                       " does not follow the last step taken");
  CurveEdit loop = e;
  loop.options = settings_.editing;
  CurveStep out;
  out.index = steps_;
  out.drag_step = e.drag_step;
  out.drag_steps = e.drag_steps;
  out.stages = run_editing_loop(current_, levels_, loop, settings_.objective(), *settings_.solver, settings_.backend, &original_);
  const EditStages& st = out.stages;
  out.solve_s = st.total_s;

  const Timer check;
  CurveStepChecks& c = out.checks;
  const bool closed = original_.closed;
  c.metrics = measure_curve(st.final, closed, original_lengths_, st.attracting);
  const Eigen::VectorXd l = segment_lengths(st.final, closed), stretch = l.cwiseQuotient(original_lengths_);
  c.total_length_error = std::abs(l.sum() - st.total_length_asked) / st.total_length_asked;
  c.segment_stretch_min = stretch.minCoeff();
  c.segment_stretch_max = stretch.maxCoeff();
  c.attractor_length_error = measure_curve(st.attracting, closed, segment_lengths(st.reference, closed), st.attracting).length_error_max;
  const double tol = rounding_tolerance(st.reference);
  c.moved_outside_support = moved_outside_support(st.reference, st.final, st.support, tol);
  c.attractor_moved_outside_support = moved_outside_support(st.reference, st.attracting, st.support, tol);
  // A drag's steps are judged together: from where its handles were before its first step,
  // against the sum of the displacements its steps asked for.
  MatrixX3 drag_start = e.drag_step == 1 ? st.reference : drag_start_;
  MatrixX3 drag_asked = e.drag_step == 1 ? MatrixX3(MatrixX3::Zero(st.reference.rows(), 3)) : drag_asked_;
  drag_asked += st.edited - st.reference;
  if (e.drag_step == e.drag_steps) {
    c.handle_reach = handle_reach(drag_start, drag_start + drag_asked, st.final, st.moved_points);
    // Where the drag asked its handles to be, against the curve's own lengths (a total length
    // lets segments stretch: only the total bounds a handle's reach there).
    MatrixX3 asked = st.edited;
    for (int p : st.moved_points) asked.row(p) = drag_start.row(p) + drag_asked.row(p);
    if (st.length_mode == LengthMode::Segments)
      c.overstretch = worst_overstretch(asked, original_lengths_, closed, 1 << (levels_ - e.edit_level), st.moved_points);
  }
  const bool every_step_in_plane = totals_.every_step_in_plane && st.solved_in_plane;
  if (original_plane_.planar) {
    c.out_of_plane = distance_from_plane(st.final, original_plane_);
    // Solved in the plane but not in it: the rows were not met (measured on the result).
    c.left_plane = every_step_in_plane && c.out_of_plane > kPlanarTolerance * original_plane_.size;
    c.self_crossings = count_self_crossings(st.final, closed, original_plane_);
    c.original_self_crossings = original_crossings_;
  }
  out.explicit_note = explicit_note(out.index, st);
  out.undone_note = undone_note(out.index, e, st, c);
  out.unmet_note = unmet_note(out.index, e, st);
  out.summary = judged(st.solve.summary, out.explicit_note, out.undone_note, out.unmet_note, settings_.accept_partial_edit, c,
                       original_plane_);
  out.summary.residual = st.solve.length_error;  // what the windows' summary leaves unmeasured
  out.check_s = check.seconds();

  // The step is taken: the session moves on from its result.
  current_.points = st.final;
  drag_start_ = std::move(drag_start);
  drag_asked_ = std::move(drag_asked);
  drag_next_ = e.drag_step == e.drag_steps ? 0 : e.drag_step + 1;
  drag_total_ = e.drag_step == e.drag_steps ? 0 : e.drag_steps;
  CurveSessionTotals& t = totals_;
  ++t.steps;
  t.solves += st.solve.solves;
  t.outer_iterations += st.solve.outer_iterations;
  t.time_s += st.total_s;
  t.explicit_s += st.explicit_s;
  t.solve_s += st.solve_s;
  t.check_s += out.check_s;
  t.every_step_in_plane = every_step_in_plane;
  t.moved_outside_support = std::max(t.moved_outside_support, c.moved_outside_support);
  t.attractor_moved_outside_support = std::max(t.attractor_moved_outside_support, c.attractor_moved_outside_support);
  t.handle_reach = std::min(t.handle_reach, c.handle_reach);
  t.explicit_length_error = std::max(t.explicit_length_error, st.explicit_step.length_error);
  t.unplaceable_midpoints += st.explicit_step.unplaceable_midpoints;
  t.explicit_notes += out.explicit_note;
  if (t.undone_note.empty()) t.undone_note = out.undone_note;
  if (t.unmet_note.empty()) t.unmet_note = out.unmet_note;
  if (!t.failed && !st.solve.converged()) {  // the budget ran out, or the numerics failed: the solver says which
    t.failed = true;
    t.failure = st.solve.summary;
    t.failure.message = edit_name(out.index) + t.failure.message;
  }
  last_ = out;
  ++steps_;
  return out;
}

SolveSummary CurveSession::outcome() const {
  if (steps_ == 0) {
    SolveSummary none;
    none.termination = Termination::Converged;
    none.message = "no step taken";
    return none;
  }
  SolveSummary s = totals_.failed ? totals_.failure : last_.stages.solve.summary;
  if (!totals_.failed) s.message = (steps_ > 1 ? edit_name(steps_ - 1) : std::string()) + s.message;
  s.iterations = totals_.solves;
  s.residual = last_.stages.solve.length_error;
  return judged(s, totals_.explicit_notes, totals_.undone_note, totals_.unmet_note, settings_.accept_partial_edit, last_.checks,
                original_plane_);
}

}  // namespace fairshape
