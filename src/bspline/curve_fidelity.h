// Is a curve constraint's pointwise error the discretization's, or is something holding the
// surface off the curve? The weak (mortar) curve rows of bspline/mortar_curve.h tie only
// weighted means of w − D along the curve, one per multiplier. Where the curve runs diagonally
// or bends across cells, the trace has modes those means do not see, and another constraint (a
// point on the path 0.2 off the curve) can move them freely: every row is met, the surface
// spikes and the pointwise error is as large as the conflict. Two yardsticks, both needed:
//  - the same curve constraint alone on the sheet (same energy, nothing else acting): its error
//    is what the weak form leaves on this path and target. A conflict is far above it where the
//    other constraint acts (compared piece by piece along the curve: the curve's worst error
//    alone may lie elsewhere and hide a small conflict); so is a
//    consistent design that bends the sheet hard across the curve (a lifted circle with pinned
//    corners: 100x), which is why this alone does not decide;
//  - refinement: a discretization error goes to 0 when the spans along the curve are refined,
//    a conflict's does not (the point still sits on the path, 0.2 off): two refinements and
//    Aitken's extrapolation estimate the error's limit. Neither does the error a kinked polyline
//    target leaves converge (Figure 2's: 0.92x per level), which the first yardstick passes, nor
//    quite the error a 48-gon path leaves where the sheet bends across it (a lifted circle with
//    pinned corners: 2e-4, 1.2e-4, 1.15e-4, 100x its error alone): the limit must also exceed a
//    stated share of the surface's size (its extent over the domain, not its control points',
//    which a degree-5 sheet spreads a thousand times wider) to count as a conflict.
// Every weak curve constraint is judged on its own: one with a large error of its own must not
// hide another's conflict.
// A conflict fails both (papers/welch-witkin/README.md, "Curve constraints that conflict").
#pragma once

#include <functional>
#include <vector>

#include "bspline/variational_sheet.h"

namespace fairshape::bspline {

//! How many samples the pointwise curve errors take along a uv polyline: enough to see every
//! leaf cell it crosses several times.
int curve_samples(const HierarchicalSurface& s, const std::vector<Eigen::Vector2d>& uv);

struct CurveConvergence {
  int constraint = -1;        // index of the curve constraint judged (a conflict, or the largest error); −1: none
  double error = 0;           // its largest |w(c(t)) − D(t)| over the samples
  double alone_error = 0;     // the same with that constraint alone on the sheet (0: not computed)
  // The piece of the curve (8 samples) judged under refinement: where its error is above
  // alone_factor × the error alone there, the one whose limit is largest against what the
  // refinements left (0: no piece judged).
  double excess_t = 0;        // where the piece starts
  double excess_error = 0, excess_alone_error = 0;  // its error and its error alone
  double refined_error = 0;   // its error with every span the curve crosses one level finer
  double twice_refined_error = 0;  // and two levels finer
  double limit = 0;           // its error's limit under refinement, extrapolated from the three
  bool conflict = false;      // above both yardsticks
};

//! Judges each weak (mortar) curve constraint of a solved sheet piece by piece (8 samples
//! each): its errors against those of the same constraint alone (a conflict needs a piece whose
//! error is > alone_factor × the error alone there and > conflict_tolerance × the surface's
//! extent) and, only for such pieces, against solves with every span the curve crosses one and
//! two levels finer (a conflict's extrapolated limit is more than limit_share of the piece's
//! last error and more than that tolerance). Returns the first conflict, or the curve with the
//! largest error. The extra solves are direct KKT solves on copies.
//! \pre the sheet holds the solution of `constraints`.
CurveConvergence curve_convergence(const VariationalSheet& sheet, const SheetEnergy& energy,
                                   const std::vector<SheetConstraint>& constraints, Backend backend, double alone_factor,
                                   double limit_share, double conflict_tolerance);

}  // namespace fairshape::bspline
