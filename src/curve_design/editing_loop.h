// The editing loop of Sauvage, Hahmann and Bonneau, "Length preserving multiresolution
// editing of curves" (§4.1, Figure 2): decompose the reference curve C_R at the edit level e,
// move control points there, reconstruct C_D; reconstruct to the wrinkle level w, fix the
// level-(w+1) lengths explicitly (explicit_length.h) and reconstruct the attracting curve C_A;
// finally smooth C_A into C_F by the length-constrained optimization (§3).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "fairshape/core/backend.h"
#include "fairshape/curve_design/curve_components.h"
#include "fairshape/curve_design/curve_plane.h"
#include "fairshape/curve_design/edit_window.h"
#include "fairshape/curve_design/explicit_length.h"
#include "fairshape/curve_design/length_problem.h"
#include "fairshape/curve_design/length_solver.h"
#include "fairshape/mesh/polyline.h"

namespace fairshape {

struct CurveMove {
  int index = 0;              // level-e control point; negative counts from the end (−1: last)
  Vec3 offset = Vec3::Zero();
  // > 0: instead of `offset`, move the point along the chord from the first control point
  // so the chord becomes this many times as long (< 1 compresses, > 1 stretches).
  double chord_scale = 0;
};

// How the loop keeps an edit local (papers/sauvage/README.md).
enum class ExplicitStep { Local, Sweep };        // explicit_local.h | explicit_length.h
enum class DetailFrames { Global, LocalFrames };  // the paper's world-coordinate details | detail_frames.h
enum class SolveRegion { Support, Curve };       // edit_window.h | the paper's whole-curve eq. 2
// Keep: a planar problem (curves and constraints in one plane) is solved in its plane
// (curve_plane.h); Free: three unknowns per point whatever the input.
enum class PlaneMode { Keep, Free };
struct EditingOptions {
  ExplicitStep explicit_step = ExplicitStep::Local;
  DetailFrames details = DetailFrames::LocalFrames;
  SolveRegion solve_region = SolveRegion::Support;
  PlaneMode plane = PlaneMode::Keep;
};

struct CurveEdit {
  int edit_level = 0;      // e
  int wrinkle_level = -1;  // w in [e, levels − 1]; −1: no explicit step (§3's method alone)
  std::vector<CurveMove> moves;
  EditingOptions options;
  int drag_step = 1, drag_steps = 1;  // this loop's place in a drag split into drag_steps loops
};

//! One edit as `steps` editing loops, each moving its handles by an equal share of the whole
//! move from the curve the previous one left (a designer's drag): offsets divided, chord scales
//! so the chord grows by equal amounts.
std::vector<CurveEdit> drag_steps(const CurveEdit& whole, int steps);

struct CurveObjective {
  const CurveEnergy* smoothness = nullptr;  // the paper's bending, or another registered energy
  double beta = 0.5;                        // (1−β)·smoothness + β·D
  std::vector<const CurveConstraintKind*> constraints;
};

struct EditStages {
  MatrixX3 reference, edited, attracting, final;  // C_R, C_D, C_A, C_F
  std::vector<int> moved_points;                  // fine-level indices
  std::vector<char> support;                      // fine-level mask of the edit's support (edit_support.h)
  ExplicitLengthReport explicit_step;
  LengthMode length_mode = LengthMode::Segments;  // which length constraint the solve kept
  double total_length_asked = 0;                  // the total length the solve aimed at
  //! The plane of C_R, C_D and C_A (curve_plane.h); solved_in_plane: the problem held its
  //! points in it (plane: keep and everything planar), so the second-order verdict is in-plane.
  CurvePlane plane;
  bool solved_in_plane = false;
  LengthSolveReport solve;
  double explicit_s = 0, solve_s = 0, total_s = 0;
};

//! Every stage of the loop up to the solve: C_D, the explicit step, C_A and the length problem.
struct PreparedCurveEdit {
  EditStages stages;  // final, solve and the times but explicit_s still empty
  std::unique_ptr<LengthProblem> problem;  // the whole curve (the paper's eq. 2)
  std::vector<EditWindow> windows;         // solve_region support: the pieces solved instead (empty: `problem`)
};
//! \throw InvalidInput as run_editing_loop.
PreparedCurveEdit prepare_editing_loop(const Polyline& reference, int levels, const CurveEdit& edit,
                                       const CurveObjective& objective, Backend backend, const Polyline* original = nullptr);

//! \throw InvalidInput for levels outside the hierarchy, moves off the level-e polygon, an
//! infeasible edit or zero-length segments (before anything is solved).
//! `original`: the curve whose lengths the edit keeps, every level's (nullptr: `reference`'s).
//! A sequence of edits (a drag) passes the first curve, so lengths never drift from step to step.
EditStages run_editing_loop(const Polyline& reference, int levels, const CurveEdit& edit, const CurveObjective& objective,
                            const LengthSolver& solver, Backend backend, const Polyline* original = nullptr);

//! The §3 objective of an edit: (1−β)·smoothness + max(β, kMinimumAttractorWeight)·D.
std::vector<WeightedStencils> paper_objective(const CurveObjective& o, int n_points, bool closed);

}  // namespace fairshape
