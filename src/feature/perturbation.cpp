#include "fairshape/feature/perturbation.h"

#include "fairshape/feature/perturbation_backends.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fairshape::feature {

MatrixX3 LevelPerturbation::dense(int n_vertices) const {
  MatrixX3 d = MatrixX3::Zero(n_vertices, 3);
  for (std::size_t i = 0; i < vertices.size(); ++i) d.row(vertices[i]) = displacement.row(static_cast<Eigen::Index>(i));
  return d;
}

LevelPerturbation collect_moved(const std::vector<int>& ids, const std::vector<Vec3>& moved, const std::vector<char>& touched) {
  LevelPerturbation out;
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (touched[i]) out.vertices.push_back(ids[i]);
  out.displacement.resize(static_cast<Eigen::Index>(out.vertices.size()), 3);
  for (std::size_t i = 0, row = 0; i < ids.size(); ++i)
    if (touched[i]) out.displacement.row(static_cast<Eigen::Index>(row++)) = moved[i].transpose();
  return out;
}

void OffsetCombiner::add(const SegmentOffset& o) {
  if (o.delta > raise.delta) raise = o;
  if (o.delta < cut.delta) cut = o;
}

Vec3 OffsetCombiner::displacement() const { return raise.delta * raise.normal + cut.delta * cut.normal; }

double cubic_profile(double s, double length, double h0, double m0, double h1, double m1) {
  const double t = s / length, t2 = t * t, t3 = t2 * t;
  return (2 * t3 - 3 * t2 + 1) * h0 + (t3 - 2 * t2 + t) * length * m0 + (-2 * t3 + 3 * t2) * h1 +
         (t3 - t2) * length * m1;
}

namespace {

// Arc length along the unrolled path of the point closest to p; < 0 when that is the path's end
// (p lies beyond the region of influence).
double arc_of_closest(const UnrolledRay& ray, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity(), arc = 0;
  for (std::size_t k = 1; k < ray.path.size(); ++k) {
    const Vec3 a = ray.path[k - 1], ab = ray.path[k] - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    const double d = (p - (a + t * ab)).squaredNorm();
    if (d < best) best = d, arc = ray.arc[k - 1] + t * (ray.arc[k] - ray.arc[k - 1]);
  }
  return arc < ray.length() * (1 - 1e-12) ? arc : -1.0;
}

}  // namespace

std::optional<SegmentOffset> segment_offset(const TriangleSurface& s, const BaseCurve& curve, int segment,
                                            const Vec3& p, OffsetMeaning meaning) {
  const BaseSegment& seg = curve.segments[static_cast<std::size_t>(segment)];
  const FeatureParams& q = curve.params;
  const double t = seg.closest_parameter(p);
  const Vec3 b = seg.a + t * seg.ab;
  const double reach = std::max(q.radius, q.right_radius());
  if ((p - b).squaredNorm() >= reach * reach) return std::nullopt;  // outside N_r (checked again below)
  // Figure 12: an end point counts only when the neighbour shares it as its closest point.
  if (t == 0.0 && seg.prev >= 0 && curve.segments[static_cast<std::size_t>(seg.prev)].closest_parameter(p) < 1.0)
    return std::nullopt;
  if (t == 1.0 && seg.next >= 0 && curve.segments[static_cast<std::size_t>(seg.next)].closest_parameter(p) > 0.0)
    return std::nullopt;
  const SurfacePoint base{seg.face, (1 - t) * seg.bary_a + t * seg.bary_b};
  const Vec3 n = s.normal(base);
  const Vec3 along = seg.ab / seg.length;
  const Vec3 left = n.cross(along).normalized();
  Vec3 dir = (p - b) - (p - b).dot(n) * n;
  dir = dir.norm() > 1e-12 * seg.length ? Vec3(dir.normalized()) : left;
  // Left and right sizes blend smoothly around the end caps (§2.7).
  const double w_left = 0.5 + 0.5 * std::clamp(dir.dot(left), -1.0, 1.0);
  const double radius = q.right_radius() + w_left * (q.radius - q.right_radius());
  if ((p - b).norm() >= radius) return std::nullopt;  // outside N_r
  const UnrolledRay ray = unroll_ray(s, base, dir, radius);
  const double length = ray.length();
  if (length <= 0) return std::nullopt;
  const double arc = arc_of_closest(ray, p);
  if (arc < 0) return std::nullopt;
  // One frame serves the whole cross-section (§1.4: the feature is small against the surface's
  // own scale); a surface that turns away within the radius breaks that, loudly.
  const double turn = std::acos(std::clamp(n.dot(s.normal(ray.end)), -1.0, 1.0)) * 180 / std::numbers::pi;
  if (turn > q.max_turn_deg)
    throw InvalidInput("feature '" + curve.name + "': the surface turns by " + std::to_string(static_cast<int>(turn)) + " degrees within radius " +
                       std::to_string(radius) + " of the curve at (" + std::to_string(b.x()) + ", " + std::to_string(b.y()) +
                       ", " + std::to_string(b.z()) + ") (face " + std::to_string(seg.face) + "; max_turn_deg " +
                       std::to_string(q.max_turn_deg) + "): the feature is too wide for this level; use a smaller "
                       "radius or draw it on a finer level");
  const double z_end = (s.point(ray.end) - b).dot(n), slope_end = ray.end_direction.dot(n);
  const double along_curve = (seg.arc_start + t * seg.length) / curve.total_length;
  const double height = q.height * (1 + (q.end_height_ratio - 1) * along_curve);
  const double target = cubic_profile(arc, length, height, q.crease, z_end, slope_end);
  if (meaning == OffsetMeaning::Displacement)  // the cubic minus the cubic through the section's own
    return SegmentOffset{cubic_profile(arc, length, height, q.crease, 0, 0), n};  // boundary values
  return SegmentOffset{target - (p - b).dot(n), n};
}

// The back ends: perturbation_reference.cpp, and perturbation_tbb.cpp in a build with TBB.
LevelPerturbation compute_perturbation(const TriangleSurface& s, const std::vector<BaseCurve>& curves,
                                       Backend backend) {
  require_backend(backend);
#if FAIRSHAPE_WITH_TBB
  return backend == Backend::Reference ? perturbation_reference(s, curves) : perturbation_tbb(s, curves);
#else
  return perturbation_reference(s, curves);
#endif
}

LevelPerturbation perturb_vertices(const TriangleSurface& s, const std::vector<BaseCurve>& curves,
                                   std::vector<int> vertices, Backend backend) {
  require_backend(backend);
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
#if FAIRSHAPE_WITH_TBB
  return backend == Backend::Reference ? perturb_vertices_reference(s, curves, vertices)
                                       : perturb_vertices_tbb(s, curves, vertices);
#else
  return perturb_vertices_reference(s, curves, vertices);
#endif
}

LevelPerturbation displace_points(const TriangleSurface& s, const std::vector<BaseCurve>& curves,
                                  const MatrixX3& points, Backend backend) {
  require_backend(backend);
#if FAIRSHAPE_WITH_TBB
  return backend == Backend::Reference ? displace_points_reference(s, curves, points)
                                       : displace_points_tbb(s, curves, points);
#else
  return displace_points_reference(s, curves, points);
#endif
}

}  // namespace fairshape::feature
