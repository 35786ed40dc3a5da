#include "fairshape/feature/feature_scale.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "fairshape/remesh/closest_point.h"

namespace fairshape::feature {
namespace {

// Largest normal curvature along the edges of f and of its edge neighbours that bends towards
// the displacement's side (`sign` of h): the change of the vertex normals per unit length, on
// edges where the surface is convex for a groove (h < 0) or concave for a ridge. Only there does
// a displacement longer than the radius of curvature fold the surface; bending the other way
// only spreads it.
double folding_curvature(const TriangleSurface& s, int f, double sign) {
  double k = 0;
  const auto edges_of = [&](int face) {
    const auto& c = s.corners(face);
    for (int i = 0; i < 3; ++i) {
      const int a = c[static_cast<std::size_t>(i)], b = c[static_cast<std::size_t>((i + 1) % 3)];
      const Vec3 edge = s.vertex(b) - s.vertex(a), turn = s.vertex_normal(b) - s.vertex_normal(a);
      const double length = edge.norm();
      // normals spread apart along a convex edge: turn · edge > 0
      if (length > 0 && -sign * turn.dot(edge) > 0) k = std::max(k, turn.norm() / length);
    }
  };
  edges_of(f);
  for (int i = 0; i < 3; ++i)
    if (s.across(f, i) >= 0) edges_of(s.across(f, i));
  return k;
}

double height_at(const BaseCurve& c, double arc) {
  return c.params.height * (1 + (c.params.end_height_ratio - 1) * arc / c.total_length);
}

}  // namespace

namespace {

// The curve's segment midpoints and the directions its heights displace them (sign(h) · normal).
struct Probes {
  MatrixX3 points, directions;
};
Probes probes_of(const TriangleSurface& surface, const BaseCurve& curve) {
  const Eigen::Index n = static_cast<Eigen::Index>(curve.segments.size());
  Probes p{MatrixX3(n, 3), MatrixX3(n, 3)};
  for (Eigen::Index i = 0; i < n; ++i) {
    const BaseSegment& seg = curve.segments[static_cast<std::size_t>(i)];
    const Vec3 normal = surface.normal(SurfacePoint{seg.face, 0.5 * (seg.bary_a + seg.bary_b)});
    const double h = height_at(curve, seg.arc_start + 0.5 * seg.length);
    p.points.row(i) = (seg.a + 0.5 * seg.ab).transpose();
    p.directions.row(i) = (h < 0 ? -normal : normal).transpose();
  }
  return p;
}

double diagonal(const SurfaceMesh& m) { return (m.positions().colwise().maxCoeff() - m.positions().colwise().minCoeff()).norm(); }

FeatureScale worst_point(const TriangleSurface& surface, const BaseCurve& curve, const Eigen::VectorXd& thickness, double size) {
  FeatureScale worst;
  double worst_ratio = -1;
  for (Eigen::Index i = 0; i < thickness.size(); ++i) {
    const BaseSegment& seg = curve.segments[static_cast<std::size_t>(i)];
    const double arc = seg.arc_start + 0.5 * seg.length;
    const double signed_h = height_at(curve, arc), h = std::abs(signed_h);
    const double k = folding_curvature(surface, seg.face, signed_h < 0 ? -1.0 : 1.0);
    const double radius = k > 0 ? 1 / k : std::numeric_limits<double>::infinity();
    double scale = size;
    std::string limit = "size";
    if (radius < scale) scale = radius, limit = "curvature";
    if (thickness[i] < scale) scale = thickness[i], limit = "thickness";
    const double ratio = scale > 0 ? h / scale : std::numeric_limits<double>::infinity();
    if (ratio > worst_ratio) worst_ratio = ratio, worst = {h, scale, arc, limit};
  }
  return worst;
}

}  // namespace

FeatureScale feature_scale(const TriangleSurface& surface, const BaseCurve& curve) {
  if (curve.segments.empty()) return {};
  const double size = diagonal(surface.mesh());
  const Probes p = probes_of(surface, curve);
  // A crossing within a millionth of the size is the curve's own face (or a rounding twin).
  const Eigen::VectorXd thickness = ClosestPointQuery(surface.mesh()).ray_distances(p.points, p.directions, 1e-6 * size);
  return worst_point(surface, curve, thickness, size);
}

FeatureScale feature_scale(const TriangleSurface& surface, const BaseCurve& curve, const SurfaceMesh& whole) {
  if (curve.segments.empty()) return {};
  const double size = diagonal(whole);
  const Probes p = probes_of(surface, curve);
  // Crossings of the part of the level that is there (exactly what the whole level gives near
  // the curve) ...
  const Eigen::VectorXd near = ClosestPointQuery(surface.mesh()).ray_distances(p.points, p.directions, 1e-6 * size);
  // ... and of the complete coarser surface, from the curve point's place on it: started from
  // the drawn level's point, a ray would cross the coarser surface's own sheet within the sag.
  const ClosestPointQuery on_whole(whole);
  const Eigen::VectorXd far = on_whole.ray_distances(on_whole.closest_points(p.points), p.directions, 1e-6 * size);
  return worst_point(surface, curve, near.cwiseMin(far), size);
}

std::string feature_scale_miss(const FeatureScale& s) {
  if (!s.exceeded()) return "";
  std::ostringstream o;
  o.precision(3);
  o << "height |h| " << s.height << " exceeds the local scale of the surface " << s.scale << " (" << s.limit
    << ") at arc length " << s.arc << ": the feature is not a fine one (the method assumes |h| below it)";
  return o.str();
}

}  // namespace fairshape::feature
