// A curve constraint w(c(s)) = D(s) that does not lock (papers/welch-witkin/README.md,
// "Curve constraints"): imposed weakly, against a space of multipliers along the curve,
//   ∫ ψ_j(s) (w(c(s)) − D(s)) ds = 0   for every ψ_j of W,
// with W the clamped B-splines of the surface's degree in the uv arc length s, with a knot
// wherever the curve crosses a grid line of its dominant direction at the surface's local
// resolution (the mortar methods' multiplier space; periodic ones round a closed curve). The
// target may be a fixed space curve or a variational curve's unknowns (mortar_rows below).
// For a curve along a parameter line W is
// exactly the space the surface traces on it, so the constraint is met exactly when the
// target is in that space and as its L² projection otherwise; for other curves W has one
// function per cell crossed, which the trace space always contains on straight pieces. Either
// way the rows are independent (no rank tolerance decides the answer) and their number does
// not depend on how densely the curves are sampled. Welch & Witkin's eq. 7 (one row per
// control point reached) is the Galerkin form of the same condition with W the whole trace
// space, whose Gram matrix has singular values spread down to rounding: which of its rows
// count as dependent decides the surface.
// Each row is normalized by ∫ψ_j, so it reads as a weighted mean of w along the curve and its
// residual is a distance in world units.
#pragma once

#include "fairshape/bspline/knot_basis.h"
#include "fairshape/bspline/surface_constraints.h"

namespace fairshape::bspline {

//! The rows of a curve whose target is a spline in t ∈ [0, 1], X(t) = Σ_i T_i(t) x_i:
//! ∫ψ_j (w(c(s)) − X(t(s))) ds / ∫ψ_j = 0 for every multiplier ψ_j reads A p − B x = 0, A
//! (m × dofs) acting on the surface's unknowns, B (m × T.size()) on the target's coefficients,
//! B_ji = ∫ψ_j T_i(t(s)) ds / ∫ψ_j. One integration for both kinds of target: a fixed space
//! curve (a polyline: hat functions, x its points, known) and a variational curve
//! (bspline/variational_curve.h: x its control points, unknowns beside the surface's).
struct MortarRows {
  SparseMatrix A, B;
};
//! Where the multipliers live. The mortar methods' rule: on the finer side, so that every mode
//! of the finer side's trace is tied to the other side and none floats free of the constraint.
//!   SurfaceTrace  the functions above (one per cell crossed, plus r): the surface follows the
//!                 target (w∘c is the target's projection where the target is coarser);
//!   Target        the target's own basis T_j(t(s)): the target follows the surface (a
//!                 variational curve finer than the sheet's trace is the trace's projection).
//! A fixed target (a polyline) always takes SurfaceTrace: its hat functions as multipliers
//! would tie the surface at every sample (eq. 7's locking).
enum class Multipliers { SurfaceTrace, Target };
//! \throw InvalidInput for fewer than two uv points, one outside the domain or a uv curve of
//! zero length.
//! `target_map` (optional, target.size() × m): the target's unknowns are y with coefficients
//! x = R y (a hierarchical variational curve, bspline/hierarchical_curve_basis.h); B then acts
//! on y, and Target multipliers are the functions Σ_i R_ij T_i (the curve's own basis).
MortarRows mortar_rows(const HierarchicalSurface& s, const std::vector<Eigen::Vector2d>& uv, const ClampedKnotBasis& target,
                       Multipliers multipliers = Multipliers::SurfaceTrace, const SparseMatrix* target_map = nullptr);
//! The number of SurfaceTrace multipliers along uv (for choosing the finer side).
//! \throw InvalidInput as mortar_rows.
int mortar_multiplier_count(const HierarchicalSurface& s, const std::vector<Eigen::Vector2d>& uv);

//! A polyline of `points` points equally spaced in t as a spline in t: degree 1, a knot at
//! every point (its coefficients are the points).
ClampedKnotBasis polyline_basis(std::size_t points);

//! The fixed-target case: A p = C with C = B D (D the space curve's points).
//! \throw InvalidInput for fewer than two points, a point outside the domain, a non-finite
//! target or a uv curve of zero length.
ConstraintRows mortar_curve_rows(const HierarchicalSurface& s, const CurveAttachment& curve);

//! One side of a tangent-continuous joint: a sheet's surface, its (u, v) curve (base-span
//! units, points equally spaced in t, paired with the other side's by t) and which side of that
//! curve the design keeps (left: to the left of the curve's direction in (u, v)).
struct JointSide {
  const HierarchicalSurface* surface = nullptr;
  std::vector<Eigen::Vector2d> uv;
  bool keep_left = true;
};
//! The derivative of w across the curve at t, along the unit (u, v) normal that points out of the
//! kept side, per unit design length (SheetShape::span_size).
Vec3 outward_derivative(const JointSide& side, const Eigen::MatrixXd& P, double t);
//! Tangent continuity of two sheets across a joint, weakly (papers/welch-witkin/README.md,
//! "Tangent-continuous joints"): leaving one sheet's kept side across the curve one enters the
//! other's, so C¹ in the design units reads ∂w₁/∂n₁ + ∂w₂/∂n₂ = 0 (n the outward normals), imposed
//! as ∫ψ_j (∂w₁/∂n₁(c₁(t)) + ∂w₂/∂n₂(c₂(t))) ds / ∫ψ_j = 0 with ψ the surface-trace multipliers of
//! the side that has more (the finer, as for the joint). Rows: first·p₁ + second·p₂ = 0.
struct TangentContinuityRows {
  SparseMatrix first, second;
};
//! \throw InvalidInput as mortar_rows, for either side.
TangentContinuityRows tangent_continuity_rows(const JointSide& first, const JointSide& second);

//! The multiplier knots (uv arc length, span units) mortar_curve_rows uses: exposed for tests.
std::vector<double> mortar_knots(const HierarchicalSurface& s, const std::vector<Eigen::Vector2d>& uv);

}  // namespace fairshape::bspline
