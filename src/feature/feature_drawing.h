// A feature as it is drawn (Khodakovsky & Schröder, "Fine level feature editing for subdivision
// surfaces", §1.4: curves are drawn directly on the surface of the level they belong to): its
// curve and profile parameters, and where its control polygon comes from — world points
// projected onto the level, a placement tool (curve_placement.h), or surface points as given.
// Placing it fills the curve's (face, barycentric) points on that level and checks that the
// feature can be shown there (papers/khodakovsky-schroder/README.md, "Features narrower than the
// finest level").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "fairshape/feature/curve_placement.h"

namespace fairshape::feature {

struct FeatureDrawing {
  FeatureCurve curve;                       // points: surface points as given, or where placing put them
  std::vector<Vec3> world_points;           // or world points, projected onto the level
  double max_distance = 0.02;               // × bounding-box diagonal: farther points leave the surface
  std::optional<CurvePlacement> placement;  // or placed by a tool (geodesic, section, file)
  std::string key;                          // its config key ("features[3]"), for messages
};

//! f.curve.points on the level `s` the feature is drawn on: its world points projected, or its
//! placement tool run (`diagonal` scales max_distance). Surface points are left as given.
//! \throw InvalidInput naming the feature and key.
void place_on_level(const TriangleSurface& s, double diagonal, FeatureDrawing& f);

//! The farthest a placed world point lies from the point it was asked at (world units; 0 when the
//! curve is given by surface points or a tool: then nothing was asked off the surface).
//! \pre place_on_level(s, ·, f) ran.
double farthest_placed_point(const TriangleSurface& s, const FeatureDrawing& f);

//! The typical finest edge under a placed curve: per control point, the mean edge of the base
//! face it lies in (uniform face ids: the base ancestor of face f on level l is f / 4^l), halved
//! for each of `levels` Loop steps; the mean over the points. The same in uniform and sparse runs
//! (both have the base mesh whole).
double finest_edge_under(const FeatureCurve& curve, const SurfaceMesh& base, int levels);

//! A feature narrower than about two edges of the finest level cannot be shown: its cubic profile
//! (§2.1.3) falls from the crest to zero within the radius, and the finest control points and the
//! limit points of the finest vertices are one sample per edge.
//! \throw InvalidConfig naming `f.key`.radius, the smaller radius of `q` (the feature's parameters
//! now or later), the finest edge and what to change (more levels or a wider radius) when a side
//! is narrower than two finest edges. \pre f.curve.points placed (uniform face ids of its level).
void check_feature_width(const FeatureDrawing& f, const FeatureParams& q, const SurfaceMesh& base, int levels);

}  // namespace fairshape::feature
