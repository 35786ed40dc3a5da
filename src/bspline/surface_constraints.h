// The geometric constraints of Welch & Witkin §4.2 as linear rows on a hierarchical B-spline
// surface's control vector, shared by x, y and z (A p = C, C with three columns):
//   point     w(u₀, v₀) = x                                     one row
//   offset    w(u₀, v₀) − w(u₁, v₁) = d: §4.2.1's "offset relationships between points", one
//             row relating the two points (linear, shared by x, y and z like the point row)
//   tangent   D_u w or D_v w at (u₀, v₀) = t, in design units      one row
//   normal    n · D_u w = 0 and n · D_v w = 0 at (u₀, v₀): two rows coupling x, y and z
//             (CoupledRows over the stacked unknowns [x; y; z]), so the tangent plane turns to
//             n with the tangents' lengths and directions in it free, whatever the history
//   curve     by default the weak (mortar) form of bspline/mortar_curve.h: one row per
//             multiplier along the curve, independent, no locking. `CurveFormulation::Paper`
//             is the transfinite constraint of eq. 7 in its gradient form: one row per control
//             point the (u, v) curve reaches, ∫ b_k(c(s)) b(c(s))ᵀ ds · p = ∫ D(s) b_k(c(s)) ds,
//             integrated over the uv arc length piece by piece between leaf-cell crossings,
//             exactly (r+1 Gauss points) or with reduced quadrature (⌈(r+1)/2⌉ points), which
//             §4.2.2 proposes against locking. Its rows are dependent in general, with singular
//             values spread down to rounding: the solvers' rank tolerance picks the surface.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "fairshape/bspline/hierarchical_surface.h"
#include "fairshape/core/types.h"

namespace fairshape::bspline {

struct ConstraintRows {
  SparseMatrix A;      // m × dofs
  Eigen::MatrixXd C;   // m × 3
};

//! A surface a space curve was traced on, kept as it was then: the curve's exact target along
//! its (u, v) path is this surface there (plus any edits), not the chords between its samples
//! (papers/welch-witkin/README.md, "Curves traced on the current surface").
struct SurfaceTrace {
  HierarchicalSurface surface;
  Eigen::MatrixXd P;
};

//! A curve in the parameter domain (a polyline in (u, v)) and the space curve it must follow,
//! both parameterized by t ∈ [0, 1] with their points equally spaced in t. With `traced` the
//! target is traced(c(t)) + the polyline of (space − traced at the samples): the surface it was
//! traced on, exactly, moved by the edits (which are sampled); `space` holds its samples.
struct CurveAttachment {
  std::vector<Eigen::Vector2d> uv;
  std::vector<Vec3> space;
  std::shared_ptr<const SurfaceTrace> traced;
};

//! The target D(t) of a curve constraint: polyline_at(space, t), or with `traced` the traced
//! surface at c(t) plus the edits' offset there.
Vec3 curve_target_at(const CurveAttachment& curve, double t);

enum class CurveQuadrature { Exact, Reduced };
enum class CurveFormulation { Mortar, Paper };

//! \throw InvalidInput for fewer than two points, a uv point outside the domain or a
//! non-finite space point.
void check_curve_attachment(const HierarchicalSurface& s, const CurveAttachment& curve);

//! \throw InvalidInput naming `what` and the point when (u, v) leaves the domain.
void check_in_domain(const HierarchicalSurface& s, double u, double v, const std::string& what);

ConstraintRows point_rows(const HierarchicalSurface& s, double u, double v, const Vec3& target);
//! w(at) − w(from) = offset. \throw InvalidInput for a point outside the domain, the two points
//! equal (the row would vanish) or a non-finite offset.
ConstraintRows offset_rows(const HierarchicalSurface& s, const Eigen::Vector2d& at, const Eigen::Vector2d& from, const Vec3& offset);
//! direction 0: D_u, 1: D_v.
ConstraintRows tangent_rows(const HierarchicalSurface& s, double u, double v, int direction, const Vec3& target);
//! Rows over the stacked unknowns [x; y; z] (3 × dofs columns), targets one column.
struct CoupledRows {
  SparseMatrix A;
  Eigen::VectorXd b;
};
//! \throw InvalidInput for a zero or non-finite normal or (u, v) outside the domain.
CoupledRows normal_rows(const HierarchicalSurface& s, double u, double v, const Vec3& normal);
//! Per-coordinate rows (shared by x, y, z) as rows over the stacked unknowns: kron(I₃, A),
//! targets [C_x; C_y; C_z].
CoupledRows stacked(const ConstraintRows& rows);
//! \throw InvalidInput for fewer than two points or a uv point outside the domain.
ConstraintRows curve_rows(const HierarchicalSurface& s, const CurveAttachment& curve, CurveQuadrature quadrature);

//! The space curve the surface currently traces along a uv polyline (a surface curve
//! "promoted" to a space curve, Figure 1), sampled at `samples` equally spaced t.
std::vector<Vec3> surface_curve(const HierarchicalSurface& s, const Eigen::MatrixXd& P,
                                const std::vector<Eigen::Vector2d>& uv, int samples);
//! The point of a polyline with equally spaced parameters at t ∈ [0, 1].
template <class Point>
Point polyline_at(const std::vector<Point>& pts, double t);

//! Stacks rows (the order of the list).
ConstraintRows stack(const std::vector<ConstraintRows>& parts, int dofs);

}  // namespace fairshape::bspline
