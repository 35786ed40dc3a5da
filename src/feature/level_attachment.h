// A feature curve's attachment to every level finer than the one it is drawn on (Khodakovsky &
// Schröder, "Fine level feature editing for subdivision surfaces", §1.4: the curve lives in the
// surface's parameter domain, so a coarse edit carries it). A point of a level-l triangle, in
// barycentric coordinates, lies in one of the four children Loop's 1:4 split makes of it; its
// coordinates there follow from the split being a midpoint split of the parameter triangle.
#pragma once

#include <vector>

#include "fairshape/feature/feature_curve.h"

namespace fairshape::feature {

//! The same parameter point one level finer: the child of p.face (children numbered as
//! subdivision/subdivider.h's child_faces: the corners at a, b, c, then the middle one) and its
//! barycentric coordinates there. \pre p.face ≥ 0 and p.bary sums to 1.
SurfacePoint child_point(const SurfacePoint& p);

//! The points where a base curve crosses the edges of its drawn level (its segments' ends,
//! the closing one written once), each followed through every finer level:
//! result[k][i] is point i on level drawn_level + k, k = 0 .. finest − drawn_level.
std::vector<std::vector<SurfacePoint>> attachments_per_level(const BaseCurve& curve, int drawn_level, int finest);

}  // namespace fairshape::feature
