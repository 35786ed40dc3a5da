// The orientation half of a ribbon constraint (Welch & Witkin §5: "ribbon constraints that
// control surface orientation as well as position along the curve"; §4.2.2's transfinite form):
// along a (u, v) curve c, the derivative of w across the curve equals a target T,
//   ∫ψ_j (∂w/∂n(c(s)) − T(s)) ds / ∫ψ_j = 0   for every multiplier ψ_j,
// n the unit (u, v) direction to the left of the curve's direction, in design units (per unit
// world length of the initial sheet, like a tangent constraint). The multipliers are the
// surface-trace ones of the position rows (bspline/mortar_curve.h), so the rows are independent
// and do not lock, and the ribbon is "curve + these rows" (variational_sheet.h).
// T is a fixed vector, or the cross derivative of a surface the ribbon was traced on (the
// initial sheet: the surface keeps the slope it had across the curve while the curve moves).
#pragma once

#include <memory>

#include "fairshape/bspline/surface_constraints.h"

namespace fairshape::bspline {

//! Rows A p = C (m × 3, shared by x, y, z) for the cross derivative along `uv` (base-span units,
//! points equally spaced in t): C's rows are `cross` when `traced` is null, else the traced
//! surface's cross derivative weighted like the rows. \throw InvalidInput as mortar_curve_rows,
//! and for a non-finite `cross`.
ConstraintRows cross_tangent_rows(const HierarchicalSurface& s, const std::vector<Eigen::Vector2d>& uv, const Vec3& cross,
                                  const SurfaceTrace* traced);

//! ∂w/∂n at t of the curve (n to the left of its direction, design units): what the rows hold.
Vec3 cross_tangent_at(const HierarchicalSurface& s, const Eigen::MatrixXd& P, const std::vector<Eigen::Vector2d>& uv, double t);

}  // namespace fairshape::bspline
