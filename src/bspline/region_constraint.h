// A sub-region constraint (Welch & Witkin §4.2.2: a transfinite constraint over "sub-regions of
// the surface", formulated as an integral over the entity): over the (u, v) rectangle R the
// surface must follow a target surface W, ∫_R (w − W)² = 0. Eq. 7's gradient form (one row
// ∫_R b_k (w − W) dA = 0 per control point reaching R) locks as the curves' did, and worse: its
// Gram rows of functions that barely reach R are nearly dependent (condition estimate 4.6e8 on
// a 16 × 16 sheet: ill_conditioned). As for the curves (bspline/mortar_curve.h) the condition is
// imposed weakly instead, against multipliers ψ on R — tensor B-splines of the surface's degree
// clamped to R with a knot at every finest grid line inside it:
//   ∫_R ψ_j (w − W) dA / ∫_R ψ_j = 0,   a weighted mean of w over R: its residual a distance.
// Their span contains the surface's trace on R, so when W lies in the surface's space (the
// sheet before any step or as it is, moved rigidly: what the config offers) the rows hold w = W
// on R exactly; on a refined sheet some are dependent (the trace is coarser than the finest
// grid somewhere in R) and the solvers drop them. Every control point reaching R is then
// determined — §4.2.2's "completely control the shape of the underlying surface span" — and the
// rest of the sheet stays free. Integrals exact: r + 1 Gauss points per direction on every
// finest grid cell of both surfaces inside R.
#pragma once

#include <functional>

#include "fairshape/bspline/surface_constraints.h"

namespace fairshape::bspline {

//! R = [lo.u, hi.u] × [lo.v, hi.v] (base-span units); the target is traced(u, v) + shift.
//! \throw InvalidInput for a corner outside the domain, an empty rectangle or a non-finite shift.
ConstraintRows region_rows(const HierarchicalSurface& s, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                           const SurfaceTrace& traced, const Vec3& shift);

//! Visits (u, v) on a grid of `per_cell` × `per_cell` points in every finest cell of R (for the
//! per-cell errors, variational_sheet.h).
void for_each_region_sample(const HierarchicalSurface& s, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, int per_cell,
                            const std::function<void(double u, double v)>& visit);

}  // namespace fairshape::bspline
