#include "fairshape/curve_design/editing_loop.h"

#include "fairshape/core/error.h"
#include "fairshape/core/timer.h"
#include "fairshape/curve_design/detail_frames.h"
#include "fairshape/curve_design/edit_support.h"
#include "fairshape/curve_design/explicit_local.h"
#include "fairshape/curves/multires_polyline.h"

namespace fairshape {
namespace {

// The reference's hierarchy with its polygon at every level (the frames of local details).
struct Levels {
  PolylineHierarchy h;
  std::vector<MatrixX3> polygons;  // polygons[j]: C_R at level j
  DetailFrames details = DetailFrames::Global;
  // d^j as used on the level-j polygon c: turned with c's segments for local frames.
  MatrixX3 detail(int j, const MatrixX3& c) const {
    return details == DetailFrames::LocalFrames ? turn_details(h.details[j], polygons[j], c, h.closed) : h.details[j];
  }
};

MatrixX3 synthesize(MatrixX3 c, const Levels& L, int from, int to, Backend backend) {
  for (int j = from; j < to; ++j) c = synthesis_step(c, L.detail(j, c), L.h.closed, backend);
  return c;
}

// The level-e index of a move (negative ones count from the end) on a polygon of m points.
int move_index(const CurveMove& mv, int m) {
  const int i = mv.index < 0 ? m + mv.index : mv.index;
  if (i < 0 || i >= m)
    throw InvalidInput("move: control point " + std::to_string(mv.index) + " is not on the level-e polygon (" +
                       std::to_string(m) + " points; negative indices count from the end)");
  return i;
}

// Applies the moves to the level-e points; returns the level-e indices moved.
std::vector<int> apply_moves(MatrixX3& c, const std::vector<CurveMove>& moves) {
  const int m = static_cast<int>(c.rows());
  std::vector<int> moved;
  const MatrixX3 before = c;
  for (const auto& mv : moves) {
    const int i = move_index(mv, m);
    if (mv.chord_scale > 0) c.row(i) = before.row(0) + mv.chord_scale * (before.row(i) - before.row(0));
    else c.row(i) += mv.offset.transpose();
    moved.push_back(i);
  }
  return moved;
}

void check_edit_placement(const Polyline& reference, int levels, const CurveEdit& e) {
  if (e.edit_level < 0 || e.edit_level > levels)
    throw InvalidInput("edit level e = " + std::to_string(e.edit_level) + " is outside the hierarchy (0.." +
                       std::to_string(levels) + ")");
  if (e.wrinkle_level != -1 && (e.wrinkle_level < e.edit_level || e.wrinkle_level >= levels))
    throw InvalidInput("wrinkle level w = " + std::to_string(e.wrinkle_level) + " must lie in [e, levels-1] = [" +
                       std::to_string(e.edit_level) + ", " + std::to_string(levels - 1) + "] (or -1: no explicit step)");
  // Level e keeps every 2^(levels−e)-th point of the finest polygon.
  const int stride = 1 << (levels - e.edit_level), n = reference.n_points();
  const int m = reference.closed ? n / stride : (n - 1) / stride + 1;
  for (const auto& mv : e.moves) (void)move_index(mv, m);
}

}  // namespace

std::vector<WeightedStencils> paper_objective(const CurveObjective& o, int n, bool closed) {
  if (!(o.beta >= 0 && o.beta <= 1)) throw InvalidInput("beta = " + std::to_string(o.beta) + " is outside [0, 1]");
  std::vector<WeightedStencils> terms;
  terms.push_back({"smoothness", 1 - o.beta, o.smoothness->stencils(n, closed)});
  std::vector<CurveStencil> distance;
  for (int i = 0; i < n; ++i) distance.push_back({1, {i, 0, 0}, {1.0, 0, 0}, i});
  terms.push_back({"attractor_distance", std::max(o.beta, kMinimumAttractorWeight), std::move(distance)});
  return terms;
}

PreparedCurveEdit prepare_editing_loop(const Polyline& reference, int levels, const CurveEdit& edit,
                                       const CurveObjective& objective, Backend backend, const Polyline* original) {
  check_edit_placement(reference, levels, edit);
  if (original == nullptr) original = &reference;
  FAIRSHAPE_ASSERT(original->n_points() == reference.n_points() && original->closed == reference.closed,
                   "the original curve has the reference's points");
  const bool closed = reference.closed;
  const int n = reference.n_points();
  PreparedCurveEdit prepared;
  EditStages& out = prepared.stages;
  out.reference = reference.points;

  Levels L;
  L.h = decompose(reference, levels, backend);
  L.details = edit.options.details;
  L.polygons.push_back(L.h.coarse);
  for (int j = 0; j < levels; ++j) L.polygons.push_back(synthesis_step(L.polygons.back(), L.h.details[j], closed, backend));
  MatrixX3 ce = L.polygons[static_cast<std::size_t>(edit.edit_level)];
  const std::vector<int> moved = apply_moves(ce, edit.moves);
  const int stride_e = 1 << (levels - edit.edit_level);
  for (int i : moved) out.moved_points.push_back(i * stride_e);
  out.support = edit_support(n, closed, levels, edit.edit_level, moved);
  out.edited = synthesize(ce, L, edit.edit_level, levels, backend);

  const Timer explicit_timer;
  if (edit.wrinkle_level >= 0) {
    const int w = edit.wrinkle_level;
    MatrixX3 cw = synthesize(ce, L, edit.edit_level, w, backend), dw = L.detail(w, cw);
    // Level w+1's lengths to restore: the finest level's are the original curve's (kept by every
    // edit); a coarser level's are not kept by the solve, so they are the reference's own.
    const Eigen::VectorXd target = segment_lengths(w + 1 == levels ? original->points : L.polygons[static_cast<std::size_t>(w + 1)], closed);
    if (edit.options.explicit_step == ExplicitStep::Local) {
      out.explicit_step = preserve_lengths_locally(cw, dw, target, closed, moved, 1 << (w - edit.edit_level));
    } else {
      const int anchor = moved.empty() ? 0 : moved.front() << (w - edit.edit_level);
      out.explicit_step = preserve_lengths_explicitly(cw, dw, target, closed, anchor, backend);
    }
    out.explicit_step.unplaceable_midpoints = count_unplaceable_midpoints(cw, target, closed);
    const MatrixX3 c_next = synthesis_step(cw, dw, closed, backend);
    out.explicit_step.length_error =
        (segment_lengths(c_next, closed) - target).cwiseAbs().cwiseQuotient(target).maxCoeff();
    out.attracting = synthesize(c_next, L, w + 1, levels, backend);
  } else {
    out.attracting = out.edited;
  }
  out.explicit_s = explicit_timer.seconds();

  const Eigen::VectorXd lengths = segment_lengths(original->points, closed);
  const CurveEditContext context{reference, out.edited, out.moved_points, lengths};
  std::vector<std::unique_ptr<CurveConstraint>> constraints;
  for (const auto* kind : objective.constraints) constraints.push_back(kind->build(context));
  out.plane = fit_plane({&out.reference, &out.edited, &out.attracting});
  if (edit.options.plane == PlaneMode::Keep && out.plane.planar) {
    std::vector<const CurveConstraint*> given;
    for (const auto& c : constraints) given.push_back(c.get());
    if (constraints_in_plane(given, out.plane)) {
      constraints.push_back(std::make_unique<InPlane>(in_plane_points(n, given), out.plane));
      out.solved_in_plane = true;
    }
  }
  prepared.problem = std::make_unique<LengthProblem>(out.attracting, closed, paper_objective(objective, n, closed),
                                                     std::move(constraints), lengths);
  out.total_length_asked = prepared.problem->total_length_target();
  out.length_mode = prepared.problem->length_mode();
  if (edit.options.solve_region == SolveRegion::Support) prepared.windows = edit_windows(*prepared.problem, out.support);
  return prepared;
}

EditStages run_editing_loop(const Polyline& reference, int levels, const CurveEdit& edit, const CurveObjective& objective,
                            const LengthSolver& solver, Backend backend, const Polyline* original) {
  const Timer total;
  PreparedCurveEdit prepared = prepare_editing_loop(reference, levels, edit, objective, backend, original);
  EditStages& out = prepared.stages;
  const Timer solve_timer;
  out.solve = prepared.windows.empty() ? solver.solve(*prepared.problem, out.attracting)
                                       : solve_windows(*prepared.problem, prepared.windows, solver);
  out.solve_s = solve_timer.seconds();
  out.final = out.solve.points;
  out.total_s = total.seconds();
  return std::move(out);
}

std::vector<CurveEdit> drag_steps(const CurveEdit& whole, int steps) {
  std::vector<CurveEdit> out;
  for (int i = 1; i <= steps; ++i) {
    CurveEdit e = whole;
    e.drag_step = i;
    e.drag_steps = steps;
    for (CurveMove& m : e.moves) {
      m.offset /= steps;
      if (m.chord_scale > 0)
        m.chord_scale = (1 + (m.chord_scale - 1) * i / steps) / (1 + (m.chord_scale - 1) * (i - 1) / steps);
    }
    out.push_back(std::move(e));
  }
  return out;
}

}  // namespace fairshape
