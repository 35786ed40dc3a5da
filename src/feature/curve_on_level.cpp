#include "fairshape/feature/curve_on_level.h"

#include <algorithm>
#include <array>

namespace fairshape::feature {
namespace {

// The corners of face f as TriangleSurface reads them (from face_halfedge on).
std::array<int, 3> corners_of(const SurfaceMesh& m, int f) {
  std::array<int, 3> c{};
  int h = m.face_halfedge(f);
  for (int i = 0; i < 3; ++i, h = m.next(h)) c[static_cast<std::size_t>(i)] = m.from_vertex(h);
  return c;
}

// Barycentric coordinates of x (on face f, up to rounding) by the normal equations, clamped into
// the face: the crossing lies on it, so only rounding is clamped away.
Vec3 barycentric_in(const SurfaceMesh& m, int f, const Vec3& x) {
  const auto c = corners_of(m, f);
  const Vec3 p0 = m.position(c[0]), e1 = m.position(c[1]) - p0, e2 = m.position(c[2]) - p0, d = x - p0;
  const double g11 = e1.dot(e1), g12 = e1.dot(e2), g22 = e2.dot(e2), det = g11 * g22 - g12 * g12;
  const double r1 = e1.dot(d), r2 = e2.dot(d);
  const double a = (g22 * r1 - g12 * r2) / det, b = (g11 * r2 - g12 * r1) / det;
  Vec3 w(1 - a - b, a, b);
  w = w.cwiseMax(0.0);
  return w / w.sum();
}

}  // namespace

CarriedCurve carry_curve(const BaseCurve& curve, const TriangleSurface& drawn, const SurfaceMesh& level,
                         const ClosestPointQuery& query, double reach) {
  std::vector<SurfacePoint> from;
  std::vector<Vec3> where;
  for (const BaseSegment& s : curve.segments) from.push_back({s.face, s.bary_a}), where.push_back(s.a);
  if (!curve.closed && !curve.segments.empty())
    from.push_back({curve.segments.back().face, curve.segments.back().bary_b}), where.push_back(curve.segments.back().b);
  const auto n = static_cast<Eigen::Index>(from.size());
  MatrixX3 points(n, 3), normals(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    points.row(i) = where[static_cast<std::size_t>(i)].transpose();
    normals.row(i) = drawn.normal(from[static_cast<std::size_t>(i)]).transpose();
  }
  std::vector<int> faces;
  const MatrixX3 crossing = query.facing_points(points, normals, reach);
  (void)query.closest_points(crossing, &faces);  // the face each crossing lies on
  CarriedCurve out{{}, MatrixX3(n, 3)};
  for (Eigen::Index i = 0; i < n; ++i) {
    const int f = faces[static_cast<std::size_t>(i)];
    const Vec3 w = barycentric_in(level, f, crossing.row(i).transpose());
    out.at.push_back({f, w});
    const auto c = corners_of(level, f);
    out.x.row(i) = (w[0] * level.position(c[0]) + w[1] * level.position(c[1]) + w[2] * level.position(c[2])).transpose();
  }
  return out;
}

double carry_reach(const BaseCurve& curve, double sum_of_heights) { return 2 * sum_of_heights + curve.reach(); }

}  // namespace fairshape::feature
