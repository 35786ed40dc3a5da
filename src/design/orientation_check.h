// Whether an edit kept the surface's orientation, measured on its result (Boier-Martin et al.
// §4.2; papers/boier-martin/README.md, "Folds and reversed normals"). The linear rows of a
// normal constraint (Q_u · N = Q_v · N = 0) are met by −N as well as N, and no energy term
// sees orientation, so a converged solve can answer with a surface turned over; a run is only
// a success when this check finds neither a flipped face nor a reversed normal. A normal
// constraint with rows `auto` is then imposed by frame rows, which only N meets (constraint.h).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "fairshape/constraint/constraint.h"
#include "fairshape/mesh/orientation.h"
#include "fairshape/subdivision/multires_surface.h"

namespace fairshape {

struct OrientationCheck {
  FoldReport folds;                   // the finest level, against the rest surface
  double normal_error_deg = -1;       // the largest angle of an achieved normal from its target (−1: none)
  std::vector<std::string> reversed;  // normal constraints met by their reverse (angle above 90°)
  bool reversed_auto = false;         // one of them has rows `auto`: frame rows would orient it
  bool folded() const { return !folds.flipped.empty() || !reversed.empty(); }
  //! What turned over, for a run's message ("" when nothing did).
  std::string describe() const;
};

//! `edited` is `rest` with an edit applied (same levels and topology).
OrientationCheck check_orientation(const MultiresSurface& rest, const MultiresSurface& edited,
                                   const DesignConstraints& placed);

//! check_orientation for many edits of one rest surface at one level (a drag's steps): the
//! edited surface is synthesized into one kept copy, and the rest faces' areas are computed once
//! (papers/boier-martin/README.md, "Folds and reversed normals": a drag step's check must cost
//! less than its solve).
class StepOrientationCheck {
 public:
  //! `rest` and `placed` must outlive this.
  StepOrientationCheck(const MultiresSurface& rest, int level, const DesignConstraints& placed);
  //! The check of `rest` with `delta` added at `level` and the finer levels synthesized.
  OrientationCheck operator()(const Eigen::MatrixXd& delta);
  //! The surface the last call checked.
  const MultiresSurface& edited() const { return edited_; }

 private:
  const MultiresSurface& rest_;
  int level_;
  const DesignConstraints& placed_;
  MultiresSurface edited_;
  RestFaces rest_faces_;
};

//! An edit solved with §4.2's tangent rows and, when its result meets a normal left to rows
//! `auto` by its reverse, solved again with frame rows (constraint.h NormalRows): `solve(frame)`
//! solves (frame: EditTerms::frame_rows_for_auto_normals), keeps its result and returns that
//! result's check. Returns what the final result's message starts with: "" after one solve.
std::string solve_orienting_normals(const std::function<OrientationCheck(bool frame_rows)>& solve);

//! `note` put before `message` ("; " between them when both say something).
std::string noted(const std::string& note, const std::string& message);

}  // namespace fairshape
