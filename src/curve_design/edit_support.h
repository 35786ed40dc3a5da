// Where an edit of Sauvage, Hahmann and Bonneau's editing loop ("Length preserving
// multiresolution editing of curves", §4.1) may change the curve. The lazy wavelet's scaling
// function of a level-e control point is a hat over its two neighbouring level-e segments, so
// moving control point i changes C_D only strictly between level-e points i−1 and i+1: that
// open interval (at the finest level) is the point's support, the union over the moved points
// the edit's support. Everything outside it is "unedited" and is meant to stay put.
#pragma once

#include <vector>

#include "fairshape/core/types.h"

namespace fairshape {

//! Fine-level mask (1 = inside the support) of moving the level-e control points `moved`
//! (level-e indices) of a curve of n points with `levels` levels.
std::vector<char> edit_support(int n_points, bool closed, int levels, int edit_level, const std::vector<int>& moved);

//! The fraction of the points outside the support that `after` moved away from `before` by
//! more than `tolerance` (0 when the support is the whole curve).
double moved_outside_support(const MatrixX3& before, const MatrixX3& after, const std::vector<char>& support,
                             double tolerance);

//! What "to rounding" means for a curve: 1e-12 of its bounding-box diagonal.
double rounding_tolerance(const MatrixX3& points);

}  // namespace fairshape
