// Derivative constraints that contradict a curve's slope. A curve constraint fixes the surface
// along its (u, v) path, so it fixes the surface's derivative along the path too: J ĉ = D' / |c'|
// (J = [D_u w, D_v w] in design units, ĉ the path's unit direction, D' the space curve's
// derivative in t, c' the path's). A tangent (J's column = t) or a normal (nᵀJ = 0, §4.2.1) at a
// point of that path asks more of the same 3 × 2 matrix J; when the conditions of every
// constraint there have no common J, no surface meets them all. The weak (mortar) rows only tie
// means of w − D along the path, so the solvers meet every row with a surface off the curve near
// the point (a flat diagonal curve and a normal on it tilted along it: energy 18.9 instead of
// 0.08, curve error 0.05, and `converged`). Decided here from the targets alone, like the
// position conflicts of bspline/constraint_coincidence.h (papers/welch-witkin/README.md,
// "Curve constraints that conflict").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "fairshape/bspline/constraint_coincidence.h"
#include "fairshape/bspline/variational_sheet.h"

namespace fairshape::bspline {

//! The slopes at a shared point, as one least-squares problem over J: the residual of the
//! best J is how far the constraints' slopes are from having a common surface (a slope, world
//! length per design length; 0 when consistent).
struct SlopeMismatch {
  Coincidence at;        // the curve and the tangent or normal on its path (at.gap: the mismatch)
  Vec3 curve_slope = Vec3::Zero();  // what the curve asks of the derivative along its path
  Eigen::Vector2d direction = Eigen::Vector2d::Zero();  // the path's unit direction, design units
};

//! The largest mismatch above `tolerance` among the tangent and normal constraints lying on a
//! weak curve constraint's path (uv within `on_path`), with every curve through that point and
//! every tangent or normal at it taken together; nothing when all are consistent.
//! \param span_size the sheet's design units per span (SheetShape::span_size).
std::optional<SlopeMismatch> slope_conflict(const std::vector<SheetConstraint>& constraints, const Eigen::Vector2d& span_size,
                                            double on_path, double tolerance);

//! The message: both constraints, where (design units), the slope the curve asks and the mismatch.
std::string describe(const SlopeMismatch& m, const std::vector<SheetConstraint>& constraints, const Eigen::Vector2d& span_size);

}  // namespace fairshape::bspline
