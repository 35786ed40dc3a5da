// A feature curve on the levels finer than the one it is drawn on, where the feature is.
// Khodakovsky & Schröder (§2.1) move every point of the neighbourhood along the normal of its
// closest base point, so the feature's crest on any finer level lies where the line through a
// drawn point along its normal meets that level. The same parameter point (face and barycentric
// coordinates followed through the 1:4 splits, level_attachment.h) is not there: Loop's rules
// are approximating, so a parameter point moves across the surface from level to level — by a
// fraction of the drawn level's edges, most where the mesh is irregular — and a curve exported
// that way runs beside the crest it should mark (papers/khodakovsky-schroder/README.md, "Exports").
#pragma once

#include <vector>

#include "fairshape/feature/feature_curve.h"
#include "fairshape/feature/triangle_surface.h"
#include "fairshape/remesh/closest_point.h"

namespace fairshape::feature {

struct CarriedCurve {
  std::vector<SurfacePoint> at;  // face of `level` (its own numbering) and barycentric coordinates
  MatrixX3 x;                    // the point there, linear in the face
};

//! The points where `curve` crosses the edges of its drawn level (its segments' ends, the closing
//! one once: as attachments_per_level lists them), each carried onto `level` — a finer level of
//! the result, or a patch of one holding the curve's region: the nearest crossing of `level`
//! within `reach` of the line through the point along the normal of `drawn` (the surface the
//! curve was built on) at it, on a face turned the same way; where there is none (the line
//! leaves past a boundary), the closest point. `query` is built on `level`.
CarriedCurve carry_curve(const BaseCurve& curve, const TriangleSurface& drawn, const SurfaceMesh& level,
                         const ClosestPointQuery& query, double reach);

//! How far along its normal a curve point may be from the crest on a finer level: the features'
//! heights at it add up (a groove dug into a ridge), and each finer level sags from the drawn one
//! by less than an edge, so twice the sum of the run's |heights| plus the curve's radius.
double carry_reach(const BaseCurve& curve, double sum_of_heights);

}  // namespace fairshape::feature
