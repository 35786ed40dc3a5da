#include "fairshape/feature/feature_curve.h"

#include <cmath>

#include "fairshape/remesh/closest_point.h"

namespace fairshape::feature {

void FeatureParams::validate(const std::string& where) const {
  const auto require = [&](bool ok, const std::string& key, double value, const std::string& range) {
    if (!ok) throw InvalidInput(where + "." + key + ": " + std::to_string(value) + " is out of range (" + range + ")");
  };
  require(radius > 0 && std::isfinite(radius), "radius", radius, "> 0");
  require(left_right_ratio > 0 && std::isfinite(left_right_ratio), "left_right_ratio", left_right_ratio, "> 0");
  require(std::isfinite(height), "height", height, "finite");
  require(std::isfinite(crease), "crease", crease, "finite");
  require(end_height_ratio >= 0 && std::isfinite(end_height_ratio), "end_height_ratio", end_height_ratio, ">= 0");
  require(flatness_angle_deg > 0 && flatness_angle_deg < 90, "flatness_angle_deg", flatness_angle_deg, "(0, 90)");
  require(max_turn_deg > 0 && max_turn_deg < 180, "max_turn_deg", max_turn_deg, "(0, 180)");
  require(profile_tolerance > 0 && profile_tolerance <= 1, "profile_tolerance", profile_tolerance, "(0, 1]");
  require(width_tolerance > 0 && width_tolerance <= 1, "width_tolerance", width_tolerance, "(0, 1]");
  require(quadratic_samples >= 1 && quadratic_samples <= 256, "quadratic_samples", quadratic_samples, "1..256");
}

namespace {

// The quadratic B-spline of the polygon (§2.4): straight from the first point to the first edge
// midpoint, a quadratic Bézier (m_{i−1}, p_i, m_i) around every inner point, straight to the end.
// A closed polygon has no first or last point: every point gets its Bézier, the midpoints taken
// around the seam, and the samples close on themselves (the last one is followed by the first).
std::vector<Vec3> quadratic_samples(const std::vector<Vec3>& p, int per_span, bool closed) {
  const std::size_t n = p.size();
  const auto bezier = [&](std::size_t i, std::size_t before, std::size_t after, int k) {
    const Vec3 m0 = 0.5 * (p[before] + p[i]), m1 = 0.5 * (p[i] + p[after]);
    const double t = static_cast<double>(k) / per_span;
    return Vec3((1 - t) * (1 - t) * m0 + 2 * t * (1 - t) * p[i] + t * t * m1);
  };
  std::vector<Vec3> out;
  if (closed) {
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < per_span; ++k) out.push_back(bezier(i, (i + n - 1) % n, (i + 1) % n, k));
    return out;
  }
  out.push_back(p.front());
  for (std::size_t i = 1; i + 1 < n; ++i)
    for (int k = 0; k <= per_span; ++k) out.push_back(bezier(i, i - 1, i + 1, k));
  out.push_back(p.back());
  return out;
}

// Refuses curves whose ends would be wrong: too short to close, a seam the height would jump
// across, or a polygon that returns to its start without saying it is closed (it would keep a
// corner there and two end caps on top of each other: the "teardrop").
void check_ends(const TriangleSurface& s, const FeatureCurve& curve) {
  const std::string where = "feature '" + curve.name + "'";
  if (curve.closed) {
    if (curve.points.size() < 3)
      throw InvalidInput(where + ": a closed curve needs at least 3 points, it has " + std::to_string(curve.points.size()));
    if (curve.params.end_height_ratio != 1.0)
      throw InvalidInput(where + ".end_height_ratio: " + std::to_string(curve.params.end_height_ratio) +
                         " on a closed curve (the height would jump at the seam; only 1 is allowed)");
    return;
  }
  if (curve.points.size() < 2)
    throw InvalidInput(where + ": a curve needs at least 2 points, it has " + std::to_string(curve.points.size()));
  const Vec3 first = s.point(curve.points.front()), last = s.point(curve.points.back());
  if (curve.points.size() > 2 && (first - last).norm() <= 1e-9 * (1 + s.longest_edge()))
    throw InvalidInput(where + ": the last point repeats the first; give closed: true and leave the repeat out (an "
                               "open curve would keep a corner and two end caps at the seam)");
}

}  // namespace

BaseCurve build_base_curve(const TriangleSurface& s, const FeatureCurve& curve) {
  check_ends(s, curve);
  curve.params.validate("feature '" + curve.name + "'");
  std::vector<SurfacePoint> polygon = curve.points;
  if (curve.params.quadratic && polygon.size() > 2) {
    std::vector<Vec3> world;
    for (const auto& p : polygon) world.push_back(s.point(p));
    const std::vector<Vec3> samples = quadratic_samples(world, curve.params.quadratic_samples, curve.closed);
    MatrixX3 m(static_cast<Eigen::Index>(samples.size()), 3);
    for (std::size_t i = 0; i < samples.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = samples[i].transpose();
    // The spline lies within the polygon's hull: a sample is never farther than the polygon's
    // deviation from the surface, so any finite bound would do; use the polygon's own length.
    double span = 0;
    for (std::size_t i = 1; i < world.size(); ++i) span += (world[i] - world[i - 1]).norm();
    polygon = project_to_surface(s, m, span, "feature '" + curve.name + "' (quadratic spline)");
    if (!curve.closed) {
      polygon.front() = curve.points.front();
      polygon.back() = curve.points.back();
    }
  }
  if (curve.closed) polygon.push_back(polygon.front());  // the walk back to the start
  BaseCurve out;
  out.name = curve.name;
  out.params = curve.params;
  out.closed = curve.closed;
  for (std::size_t i = 1; i < polygon.size(); ++i) {
    std::vector<FacePiece> pieces;
    try {
      pieces = walk_between(s, polygon[i - 1], polygon[i]);
    } catch (const InvalidInput& e) {
      throw InvalidInput("feature '" + curve.name + "', between points " + std::to_string(i - 1) + " and " +
                         std::to_string(i % (curve.closed ? polygon.size() - 1 : polygon.size())) + ": " + e.what());
    }
    for (const FacePiece& piece : pieces) {
      BaseSegment seg;
      seg.face = piece.face;
      seg.bary_a = piece.from;
      seg.bary_b = piece.to;
      seg.a = s.point({piece.face, piece.from});
      seg.b = s.point({piece.face, piece.to});
      seg.ab = seg.b - seg.a;
      seg.length = seg.ab.norm();
      seg.inv_length2 = 1 / seg.ab.squaredNorm();
      if (seg.length <= 1e-12 * (1 + seg.a.norm())) continue;  // a crossing exactly at a vertex
      seg.arc_start = out.total_length;
      out.total_length += seg.length;
      out.segments.push_back(seg);
    }
  }
  const int n = static_cast<int>(out.segments.size());
  for (int i = 0; i < n; ++i) {
    // Around a closed curve every segment has both neighbours, so the locally-closest test of
    // Figure 12 treats the seam like any other joint and no end cap forms there.
    out.segments[static_cast<std::size_t>(i)].prev = i > 0 ? i - 1 : curve.closed ? n - 1 : -1;
    out.segments[static_cast<std::size_t>(i)].next = i + 1 < n ? i + 1 : curve.closed ? 0 : -1;
  }
  if (out.segments.empty()) throw InvalidInput("feature '" + curve.name + "': every point of the curve coincides");
  return out;
}

std::vector<SurfacePoint> project_to_surface(const TriangleSurface& s, const MatrixX3& points, double max_distance,
                                             const std::string& what) {
  std::vector<int> faces;
  const MatrixX3 closest = s.locator().closest_points(points, &faces);
  std::vector<SurfacePoint> out;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const double distance = (points.row(i) - closest.row(i)).norm();
    if (!(distance <= max_distance))
      throw InvalidInput(what + ": point " + std::to_string(i) + " (" + std::to_string(points(i, 0)) + ", " +
                         std::to_string(points(i, 1)) + ", " + std::to_string(points(i, 2)) + ") is " +
                         std::to_string(distance) + " from the surface (at most " + std::to_string(max_distance) +
                         " allowed): the curve leaves the surface");
    const int f = faces[static_cast<std::size_t>(i)];
    Vec3 b = s.barycentric(f, closest.row(i).transpose());
    for (int k = 0; k < 3; ++k) b[k] = std::max(b[k], 0.0);
    out.push_back({f, b / b.sum()});
  }
  return out;
}

}  // namespace fairshape::feature
