// Ways to place a feature curve on the level it is drawn on, besides listing its control points:
// a geodesic through waypoints, a plane section, a polyline read from a file (Khodakovsky &
// Schröder, "Fine level feature editing for subdivision surfaces", §1.4: curves are drawn
// directly on the surface). Each yields the control polygon of a FeatureCurve on that level.
#pragma once

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "fairshape/feature/feature_curve.h"

namespace fairshape::feature {

//! Points on the level: world points (each projected to its closest point, at most
//! `max_distance` away) or surface points as given.
struct PointsOnSurface {
  std::vector<Vec3> world;
  std::vector<SurfacePoint> surface;
  std::size_t size() const { return world.empty() ? surface.size() : world.size(); }
};

struct GeodesicPlacement {
  PointsOnSurface through;  // the waypoints, in order
  double spacing = 0;       // > 0: control points this far apart (world units); 0: the path's corners
  int smooth = 0;           // umbrella smoothing steps on the surface (waypoints stay)
};

struct SectionPlacement {
  Vec3 point = Vec3::Zero(), normal = Vec3::UnitZ();  // the plane
  std::optional<Vec3> nearest;                         // picks the component (default: point)
  std::optional<Vec3> from, to;                        // clip between the closest points to these
  bool long_arc = false;                               // on a loop: the longer way from → to
  double spacing = 0;                                  // as for a geodesic
};

struct PolylineFilePlacement {
  std::string path;  // resolved already
};

using CurvePlacement = std::variant<GeodesicPlacement, SectionPlacement, PolylineFilePlacement>;

struct PlacedCurve {
  std::vector<SurfacePoint> points;
  bool closed = false;
};

//! The control polygon `how` describes on `s`. `closed` asks for a closed curve (a geodesic
//! back to its first waypoint, a file's polyline closed); a section taken whole is closed when
//! its component is a loop. Messages name the feature and its config key `key` ("feature 'rim'
//! (features[2].section.from): ...").
//! \throw InvalidInput naming both: a waypoint or file point off the surface, waypoints on
//! different components, a plane that misses the surface, clip points far from the section.
PlacedCurve place_curve(const TriangleSurface& s, const CurvePlacement& how, bool closed, double max_distance,
                        const std::string& feature, const std::string& key);

//! World points projected, or surface points checked against `s` (face index, weights).
std::vector<SurfacePoint> points_on(const TriangleSurface& s, const PointsOnSurface& p, double max_distance,
                                    const std::string& where);

}  // namespace fairshape::feature
