// Self-crossings of a planar polyline: a drag that folds a leg across another leaves every
// length kept and every solver converged, so it is looked for on the result
// (papers/sauvage/README.md, "Self-crossings"). Segments are hashed into a uniform grid of about
// one segment per cell, so the count is O(n) expected (much less than a solve), not O(n²).
#pragma once

#include "fairshape/core/types.h"
#include "fairshape/curve_design/curve_plane.h"

namespace fairshape {

//! Pairs of non-adjacent segments of X (closed: the closing segment too) that cross or touch,
//! in the coordinates of `plane` (X's distance from it is ignored: measured elsewhere).
int count_self_crossings(const MatrixX3& X, bool closed, const CurvePlane& plane);

}  // namespace fairshape
