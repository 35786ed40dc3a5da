// Is a curve constraint's pointwise error the discretization's, or is another constraint
// holding the surface off the curve? The weak (mortar) curve rows of bspline/mortar_curve.h tie
// only weighted means of w − D along the curve, one per multiplier; along a diagonal or bent
// path the trace has modes those means do not see, so every row can be met while the surface
// spikes. Two questions, answered apart:
//  - a conflict: another constraint on the path asking another position (a point, a crossing or
//    overlapping curve). Decided exactly from the targets at the shared parameter point
//    (bspline/constraint_coincidence.h): the run ends constraints_unmet;
//  - resolution: with no such coincidence the continuous problem is consistent (a point beside
//    the path, however close, costs finite energy), but the discrete surface may still be far
//    from the curve (a point 0.01 beside the path asking 0.1 more: 6 % of the sheet at 8
//    spans). The probe compares the curve's errors, piece by piece along it (8 samples each),
//    with those of the same constraint alone on the sheet, and where they are well above, with
//    solves whose spans along the curve (a band one leaf cell wide) are one and two levels
//    finer; Aitken's extrapolation estimates each piece's limit. A limit that stays is reported
//    as `unresolved` — a warning in the run's message, with refinement.tolerance the way to
//    refine — not as a conflict: tangent and normal constraints on a path, which are not
//    compared exactly, are the only conflicts it stands for.
// (papers/welch-witkin/README.md, "Curve constraints that conflict").
#pragma once

#include <functional>
#include <vector>

#include <optional>
#include <string>

#include "fairshape/bspline/constraint_coincidence.h"
#include "fairshape/bspline/slope_conflict.h"
#include "fairshape/bspline/variational_sheet.h"

namespace fairshape::bspline {

//! How many samples the pointwise curve errors take along a uv polyline: enough to see every
//! leaf cell it crosses several times.
int curve_samples(const HierarchicalSurface& s, const std::vector<Eigen::Vector2d>& uv);

struct CurveConvergence {
  int constraint = -1;        // index of the curve constraint judged (unresolved, or the largest error); −1: none
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
  bool unresolved = false;    // a piece's error stays under refinement
  //! Another constraint meeting the curve next to the unresolved piece (the same position asked:
  //! a crossing curve, a tangent, a normal): then what stays is a conflict of slopes
  //! (constraints_unmet); without one, a warning on the resolution.
  std::optional<Coincidence> meeting;
};

//! A point or curve on a weak curve constraint's path (within a millionth of the domain) asking a
//! position more than conflict_tolerance × the surface's extent from the curve's: the largest.
std::optional<Coincidence> curve_conflict(const VariationalSheet& sheet, const std::vector<SheetConstraint>& constraints,
                                          double conflict_tolerance);

//! A tangent or normal on a weak curve constraint's path whose slope differs from the curve's
//! there by more than slope_tolerance (bspline/slope_conflict.h): the largest.
std::optional<SlopeMismatch> curve_slope_conflict(const VariationalSheet& sheet, const std::vector<SheetConstraint>& constraints,
                                                  double slope_tolerance);

//! The probe of every weak (mortar) curve constraint of a solved sheet: its pieces' errors
//! against alone_factor × the error alone there and conflict_tolerance × the surface's extent,
//! then two refinements along it (unresolved when a piece's extrapolated limit is more than
//! limit_share of its last error and that tolerance). Returns the first unresolved curve, else
//! the one with the largest error. The extra solves are direct KKT solves on copies.
//! \pre the sheet holds the solution of `constraints`.
CurveConvergence curve_convergence(const VariationalSheet& sheet, const SheetEnergy& energy,
                                   const std::vector<SheetConstraint>& constraints, Backend backend, double alone_factor,
                                   double limit_share, double conflict_tolerance);

//! The message of an unresolved curve (c.unresolved): with c.meeting the conflict of slopes,
//! else a warning on the resolution — where, how large, what it can mean.
std::string describe_unresolved(const CurveConvergence& c, const std::vector<SheetConstraint>& constraints);

}  // namespace fairshape::bspline
