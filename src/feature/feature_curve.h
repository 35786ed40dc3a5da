// A feature curve (Khodakovsky & Schröder, "Fine level feature editing for subdivision
// surfaces", §1.4, §2.4, §2.7): a control polygon drawn on one level of a Loop hierarchy, the
// parameters of its profile, and the base polyline the perturbation is measured from.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "fairshape/feature/ray_unrolling.h"
#include "fairshape/feature/triangle_surface.h"

namespace fairshape::feature {

//! Per-feature parameters (§2.7). Lengths are world units.
struct FeatureParams {
  double radius = 0.1;             // neighbourhood size r on the left of the curve
  double left_right_ratio = 1.0;   // r_left / r_right
  double height = 0.02;            // profile value at the base point (negative: a groove)
  double crease = 0.0;             // profile slope at the base point (0: smooth)
  double end_height_ratio = 1.0;   // height at the curve's end / height at its start
  double flatness_angle_deg = 2.0;  // adaptive refinement threshold (§2.5)
  double max_turn_deg = 60.0;       // the surface may turn at most this much within the radius
  bool quadratic = false;          // frames on the quadratic spline of the polygon (§2.4)
  int quadratic_samples = 8;       // straight pieces per quadratic span
  // How closely the visible surface (finest level, limit) must show the profile
  // (profile_measure.h): height and profile errors as a fraction of |height|, widths as a
  // fraction of the radius. A feature that misses them is reported, and its run not converged.
  double profile_tolerance = 0.02;
  double width_tolerance = 0.02;
  double right_radius() const { return radius / left_right_ratio; }
  //! \throw InvalidInput naming the parameter and its valid range.
  void validate(const std::string& where) const;
};

struct FeatureCurve {
  std::string name;
  int level = 0;                     // the hierarchy level it is drawn on
  std::vector<SurfacePoint> points;  // control polygon on that level's mesh
  FeatureParams params;
  //! The polygon goes on from its last point back to its first: no end, no end cap, and the
  //! quadratic spline is periodic (a repeated first point would leave a corner and two caps).
  bool closed = false;
};

//! One straight piece of a base curve, inside one face of the level (Figure 5).
struct BaseSegment {
  int face = -1;
  Vec3 a = Vec3::Zero(), b = Vec3::Zero();            // end points in space
  Vec3 bary_a = Vec3::Zero(), bary_b = Vec3::Zero();  // and in the face
  Vec3 ab = Vec3::Zero();                             // b − a, and 1 / |b − a|² (closest points
  double inv_length2 = 0;                             // are the hot loop of the perturbation)
  double arc_start = 0, length = 0;                   // arc length along the curve
  int prev = -1, next = -1;                           // neighbouring segments of the same curve

  //! Parameter in [0, 1] of the point closest to p, and the squared distance to it (inline:
  //! the perturbation tests every listed segment against every vertex near the curve).
  double closest_parameter(const Vec3& p) const { return std::clamp((p - a).dot(ab) * inv_length2, 0.0, 1.0); }
  double squared_distance(const Vec3& p) const { return (p - (a + closest_parameter(p) * ab)).squaredNorm(); }
};

struct BaseCurve {
  std::string name;
  std::vector<BaseSegment> segments;  // closed: the last one's next is the first one
  double total_length = 0;
  FeatureParams params;
  bool closed = false;
  //! How far from the curve its profile reaches: the wider of its two sides.
  double reach() const { return std::max(params.radius, params.right_radius()); }
  //! Distance from p to the nearest of its segments.
  double distance_to(const Vec3& p) const {
    double d2 = std::numeric_limits<double>::infinity();
    for (const BaseSegment& s : segments) d2 = std::min(d2, s.squared_distance(p));
    return std::sqrt(d2);
  }
};

//! The polygon split at every edge of the level (and, when params.quadratic, replaced by the
//! quadratic spline through its edge midpoints, sampled and walked on the surface). A closed
//! curve also walks from its last point to its first, its segments link around, and its spline
//! has a span at every point.
//! \throw InvalidInput when the curve leaves the surface, has fewer than 2 points (3 when
//! closed), ends where it starts without being closed, or is closed with end_height_ratio ≠ 1.
BaseCurve build_base_curve(const TriangleSurface& s, const FeatureCurve& curve);

//! World points projected to their closest points on `s` (CGAL AABB tree). \throw InvalidInput
//! naming the first point farther than `max_distance` from the surface.
std::vector<SurfacePoint> project_to_surface(const TriangleSurface& s, const MatrixX3& points, double max_distance,
                                             const std::string& what);

}  // namespace fairshape::feature
