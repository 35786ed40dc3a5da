// Khodakovsky & Schröder's standing assumption ("Fine level feature editing for subdivision
// surfaces", §2.2 and §3): a feature is small against the local scale of the surface it is
// carved into. A feature taller than that folds into the surface, reaches through a thin part,
// or dwarfs the model; its profile may still be met exactly, so the profile measures alone would
// call it a success. This check says so instead.
//
// The local scale at a point of the curve is the smallest of
//  - the radius of curvature there: the change of the surface's normal field across the face
//    and its edge neighbours, per unit length;
//  - the surface's thickness in the direction the feature displaces (sign(h) · normal): the
//    distance to the next crossing of the surface;
//  - the size of the surface (its bounding-box diagonal).
// It is evaluated on the surface the curve is drawn on, before the feature, at every segment
// midpoint of the curve.
#pragma once

#include <string>

#include "fairshape/feature/feature_curve.h"
#include "fairshape/feature/triangle_surface.h"

namespace fairshape::feature {

struct FeatureScale {
  double height = 0;   // |h| where the ratio |h| / scale is largest
  double scale = 0;    // the local scale there
  double arc = 0;      // arc length of that point along the curve
  std::string limit;   // which bound set the scale: "curvature", "thickness", "size"
  bool exceeded() const { return height > scale; }
};

//! The point of `curve` where its height is largest against the local scale of `surface`.
FeatureScale feature_scale(const TriangleSurface& surface, const BaseCurve& curve);

//! The same where `surface` holds only part of the level (a sparse run's patch around the curve,
//! adaptive_evaluation.h): the curvature on `surface` (the curve's faces and their neighbours are
//! in it), the thickness the smaller of the crossings of `surface` and of `whole` — a complete
//! surface of the model without features, coarser than `surface` (a sparse run's base mesh: a
//! thin part away from the computed region is only there), the ray cast from the curve point's
//! closest point on it — and the size that of `whole`. A coarser `whole` stands in for the
//! surface within its sag of the drawn level (a fraction of its edges).
FeatureScale feature_scale(const TriangleSurface& surface, const BaseCurve& curve, const SurfaceMesh& whole);

//! "" when the feature fits, else "height |h| 5 exceeds the local scale 2.83 (size) at arc length 0.41".
std::string feature_scale_miss(const FeatureScale& s);

}  // namespace fairshape::feature
