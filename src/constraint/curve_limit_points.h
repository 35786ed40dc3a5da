// A curve constraint placed on the limit surface (placement `limit_points`): the designer's
// control polygon sampled densely and each sample moved to its closest point of a level's
// limit surface (subdivision/limit_evaluation.h). In place of the Appendix's
// re-parameterization ("Detail-preserving variational surface design with multiresolution
// constraints"), no vertex is snapped: the constrained points are the exact surface points, and
// (AP) is asked of them on the limit surface:
//   (AP) consecutive samples lie in the same face or in faces sharing a vertex, in curve order,
// so the chain of constrained points follows the curve across every face it crosses.
#pragma once

#include <string>
#include <vector>

#include "fairshape/constraint/constraint.h"

namespace fairshape {

struct LimitCurve {
  std::vector<SurfacePoint> points;  // in curve order
  std::vector<double> source;        // each point's control-polygon parameter (segment + fraction)
  std::vector<Vec3> on_curve;        // the polygon point each one was projected from
};

//! Samples the control polygon at steps of at most `step` and places each sample at its
//! closest limit point; where two consecutive points break (AP), the polygon is bisected
//! between them (up to 2^12 times per gap). \throw InvalidInput naming `who` when a sample lies
//! farther than `max_distance` from the limit surface or (AP) cannot be reached.
LimitCurve place_on_limit(const LimitEvaluator& evaluator, const MatrixX3& control, bool closed, double step,
                          double max_distance, const std::string& who);

}  // namespace fairshape
