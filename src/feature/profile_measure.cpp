#include "fairshape/feature/profile_measure.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "fairshape/feature/feature_scale.h"
#include "fairshape/remesh/closest_point.h"

namespace fairshape::feature {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double reach_of(const BaseCurve& c) { return std::max(c.params.radius, c.params.right_radius()); }

// The closest point of a curve to p: distance, base point, and which side of the curve p is on.
struct NearCurve {
  double distance = std::numeric_limits<double>::infinity();
  int segment = -1;
  double t = 0;
};
NearCurve near_curve(const BaseCurve& c, const Vec3& p) {
  NearCurve best;
  for (int k = 0; k < static_cast<int>(c.segments.size()); ++k) {
    const double d2 = c.segments[static_cast<std::size_t>(k)].squared_distance(p);
    if (d2 < best.distance * best.distance)
      best = {std::sqrt(d2), k, c.segments[static_cast<std::size_t>(k)].closest_parameter(p)};
  }
  return best;
}

// A curve's box widened by `pad`: most points of a fine level are far from a curve, and this
// rejects them before the scan over its segments.
struct Box {
  Vec3 lo, hi;
  Box(const BaseCurve& c, double pad) : lo(Vec3::Constant(1e300)), hi(Vec3::Constant(-1e300)) {
    for (const BaseSegment& s : c.segments) lo = lo.cwiseMin(s.a.cwiseMin(s.b)), hi = hi.cwiseMax(s.a.cwiseMax(s.b));
    lo.array() -= pad, hi.array() += pad;
  }
  bool contains(const Vec3& p) const { return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all(); }
};

struct Other {
  const BaseCurve* curve;
  Box box;
};
using Others = std::vector<Other>;

bool near_other(const Others& others, const Vec3& p) {
  for (const Other& o : others)
    if (o.box.contains(p) && near_curve(*o.curve, p).distance < reach_of(*o.curve)) return true;
  return false;
}

struct Frame {
  Vec3 b, n, left;
};
Frame frame_at(const TriangleSurface& s, const BaseCurve& c, int segment, double t) {
  const BaseSegment& seg = c.segments[static_cast<std::size_t>(segment)];
  const Vec3 n = s.normal(SurfacePoint{seg.face, (1 - t) * seg.bary_a + t * seg.bary_b});
  return {seg.a + t * seg.ab, n, n.cross(seg.ab / seg.length).normalized()};
}

double requested_height(const BaseCurve& c, int segment, double t) {
  const BaseSegment& seg = c.segments[static_cast<std::size_t>(segment)];
  const double along = (seg.arc_start + t * seg.length) / c.total_length;
  return c.params.height * (1 + (c.params.end_height_ratio - 1) * along);
}

// The finest faces of a reference surface, to find the face below a curve sample (one per
// surface: an AABB tree of the finest level is the costly part of the measurement).
struct FinestFaces {
  SurfaceMesh mesh;
  ClosestPointQuery locate;
  TriangleSurface faces;
  FinestFaces(const SurfaceMesh& finest, const MatrixX3& positions)
      : mesh(with_positions(finest, positions)), locate(mesh), faces(mesh, MatrixX3::Zero(mesh.n_vertices(), 3)) {}
  static SurfaceMesh with_positions(SurfaceMesh m, const MatrixX3& x) {
    m.positions() = x;
    return m;
  }
};

// One surface (finest control points or limit points): where the feature was applied to, what
// was asked of it, and what it is.
struct Surfaces {
  const MatrixX3& reference;
  const MatrixX3& requested;
  const MatrixX3& achieved;
  const FinestFaces& below;
};

// Samples of the curve for its height: about one per finest edge — the longest edge of the face a
// segment lies in on its drawn level, halved for each level between it and the finest (Loop
// halves the edges). Local, so that a run that computes only the curve's region (a sparse run)
// samples exactly where the uniform run does.
std::vector<std::pair<int, double>> height_samples(const TriangleSurface& level, const BaseCurve& curve, int levels_to_finest) {
  std::vector<std::pair<int, double>> at;
  const double shrink = std::ldexp(1.0, -levels_to_finest);
  for (int k = 0; k < static_cast<int>(curve.segments.size()); ++k) {
    const BaseSegment& seg = curve.segments[static_cast<std::size_t>(k)];
    const auto& c = level.corners(seg.face);
    double edge = 0;
    for (int i = 0; i < 3; ++i) edge = std::max(edge, (level.vertex(c[(i + 1) % 3]) - level.vertex(c[i])).norm());
    const int n = std::max(1, static_cast<int>(std::ceil(seg.length / (edge * shrink))));
    for (int i = 0; i < n; ++i) at.emplace_back(k, (i + 0.5) / n);
  }
  return at;
}

ProfileMeasure measure_one(const SurfaceMesh& finest, const Surfaces& x, const TriangleSurface& level,
                           const BaseCurve& curve, const Others& others, double scale, int levels_to_finest) {
  ProfileMeasure m;
  // Profile error and widths over the finest vertices near the curve.
  double sum_a[2] = {0, 0}, moment_a[2] = {0, 0}, sum_t[2] = {0, 0}, moment_t[2] = {0, 0};
  const double margin = measured_reach(level, curve);
  const Box box(curve, margin);
  for (int v = 0; v < finest.n_vertices(); ++v) {
    const Vec3 p = x.reference.row(v).transpose();
    if (!box.contains(p)) continue;
    const NearCurve near = near_curve(curve, p);
    // Other features are tested where the requested surface is: a finer feature's curve lies
    // on this feature's displaced surface, not on the surface it was applied to.
    if (near.distance >= margin || near_other(others, x.requested.row(v).transpose())) continue;
    const Vec3 achieved = (x.achieved.row(v) - x.reference.row(v)).transpose();
    const Vec3 requested = (x.requested.row(v) - x.reference.row(v)).transpose();
    m.profile_error = std::max(m.profile_error, (achieved - requested).norm() / scale);
    const Frame f = frame_at(level, curve, near.segment, near.t);
    const int side = (p - f.b).dot(f.left) >= 0 ? 0 : 1;
    const double a = std::abs(achieved.dot(f.n)), t = std::abs(requested.dot(f.n));
    sum_a[side] += a, moment_a[side] += a * near.distance;
    sum_t[side] += t, moment_t[side] += t * near.distance;
  }
  const double radius[2] = {curve.params.radius, curve.params.right_radius()};
  double width[2];
  for (int side : {0, 1}) {
    width[side] = sum_a[side] > 0 && sum_t[side] > 0 && moment_t[side] > 0
                      ? radius[side] * (moment_a[side] / sum_a[side]) / (moment_t[side] / sum_t[side])
                      : kNaN;
    if (std::isfinite(width[side])) m.width_error = std::max(m.width_error, std::abs(width[side] - radius[side]) / radius[side]);
  }
  m.width_left = width[0], m.width_right = width[1];
  // Heights at samples of the base curve, about one per finest edge, in the finest face below.
  const TriangleSurface& faces = x.below.faces;
  const std::vector<std::pair<int, double>> at = height_samples(level, curve, levels_to_finest);
  MatrixX3 samples(static_cast<Eigen::Index>(at.size()), 3);
  for (std::size_t i = 0; i < at.size(); ++i)
    samples.row(static_cast<Eigen::Index>(i)) = frame_at(level, curve, at[i].first, at[i].second).b.transpose();
  std::vector<int> face_of;
  const MatrixX3 below = x.below.locate.closest_points(samples, &face_of);
  m.height_min = std::numeric_limits<double>::infinity(), m.height_max = -m.height_min;
  for (std::size_t i = 0; i < at.size(); ++i) {
    const Frame f = frame_at(level, curve, at[i].first, at[i].second);
    if (near_other(others, f.b) || near_other(others, f.b + requested_height(curve, at[i].first, at[i].second) * f.n)) continue;
    const int face = face_of[i];
    const Vec3 w = faces.barycentric(face, below.row(static_cast<Eigen::Index>(i)).transpose());
    double h = 0;
    for (int c = 0; c < 3; ++c) {
      const int v = faces.corners(face)[static_cast<std::size_t>(c)];
      h += w[c] * (x.achieved.row(v) - x.reference.row(v)).dot(f.n.transpose());
    }
    m.height_min = std::min(m.height_min, h), m.height_max = std::max(m.height_max, h);
    m.height_error = std::max(m.height_error, std::abs(h - requested_height(curve, at[i].first, at[i].second)) / scale);
  }
  if (!std::isfinite(m.height_min)) m.height_min = m.height_max = kNaN;
  return m;
}

double error_scale(const FeatureParams& q) {
  const double scale = std::max(std::abs(q.height), std::abs(q.height * q.end_height_ratio));
  return scale > 0 ? scale : q.radius;  // a crease alone: errors as fractions of the radius
}

std::string miss(const char* where, const ProfileMeasure& m, const FeatureParams& q) {
  std::ostringstream o;
  o.precision(3);
  if (m.profile_error > q.profile_tolerance)
    o << where << ": profile error " << m.profile_error << " of |h| > profile_tolerance " << q.profile_tolerance;
  else if (m.height_error > q.profile_tolerance)
    o << where << ": height error " << m.height_error << " of |h| > profile_tolerance " << q.profile_tolerance;
  else if (m.width_error > q.width_tolerance)
    o << where << ": width error " << m.width_error << " of r > width_tolerance " << q.width_tolerance;
  return o.str();
}

}  // namespace

double measured_reach(const TriangleSurface& level, const BaseCurve& curve) {
  double edge = 0;
  for (const BaseSegment& seg : curve.segments) {
    const auto& c = level.corners(seg.face);
    for (int i = 0; i < 3; ++i) edge = std::max(edge, (level.vertex(c[(i + 1) % 3]) - level.vertex(c[i])).norm());
  }
  return reach_of(curve) + edge;
}

ProfileMeasure measure_on_mesh(const SurfaceMesh& mesh, const MatrixX3& reference, const MatrixX3& requested,
                               const MatrixX3& achieved, const TriangleSurface& level, const BaseCurve& curve,
                               const std::vector<const BaseCurve*>& others, int levels_to_finest) {
  const FinestFaces below(mesh, reference);
  Others near;
  for (const BaseCurve* c : others) near.push_back({c, Box(*c, reach_of(*c))});
  return measure_one(mesh, {reference, requested, achieved, below}, level, curve, near, error_scale(curve.params),
                     levels_to_finest);
}

std::string profile_miss(const char* where, const ProfileMeasure& m, const FeatureParams& q) { return miss(where, m, q); }

ProfileGates profile_gates(ProfileTarget target) {
  switch (target) {
    case ProfileTarget::Limit: return {false, true};
    case ProfileTarget::Finest: return {true, false};
    case ProfileTarget::DrawnLevel: break;
  }
  return {true, true};
}

const char* gates_name(ProfileGates g) { return g.fine && g.limit ? "finest+limit" : g.fine ? "finest" : "limit"; }

std::vector<FeatureMeasure> measure_features(FeaturedSurface& surface) {
  const MultiresSurface& result = surface.result();
  const std::vector<LevelOperator>& ops = surface.operators();
  const VisibleTargets& targets = surface.visible_targets();
  std::vector<FeatureMeasure> out;
  if (ops.empty()) return out;
  const ProfileGates gates = profile_gates(surface.profile_target());
  const SurfaceMesh& finest = result.mesh(result.levels());
  const MatrixX3& achieved_fine = finest.positions();
  const MatrixX3 achieved_limit = targets.limit_matrix * achieved_fine;
  std::vector<const BaseCurve*> all;
  for (const LevelOperator& op : ops)
    for (const BaseCurve& c : op.curves) all.push_back(&c);
  for (std::size_t k = 0; k < ops.size(); ++k) {
    const FinestFaces fine_below(finest, targets.fine[k]), limit_below(finest, targets.limit[k]);
    for (std::size_t j = 0; j < ops[k].curves.size(); ++j) {
      const BaseCurve& curve = ops[k].curves[j];
      Others others;
      for (const BaseCurve* c : all)
        if (c != &curve) others.push_back({c, Box(*c, reach_of(*c))});
      const FeatureParams& q = curve.params;
      const double scale = error_scale(q);
      FeatureMeasure f;
      f.id = ops[k].ids[j];
      f.name = curve.name;
      f.level = ops[k].level;
      const int below = result.levels() - ops[k].level;
      f.fine = measure_one(finest, {targets.fine[k], targets.fine.back(), achieved_fine, fine_below}, *ops[k].surface, curve,
                           others, scale, below);
      f.limit = measure_one(finest, {targets.limit[k], targets.limit.back(), achieved_limit, limit_below}, *ops[k].surface,
                            curve, others, scale, below);
      if (gates.fine) f.why = miss("finest level", f.fine, q);
      if (f.why.empty() && gates.limit) f.why = miss("limit", f.limit, q);
      // A profile met exactly is still not a fine feature when it dwarfs the surface there.
      const std::string too_tall = feature_scale_miss(feature_scale(*ops[k].surface, curve));
      if (!too_tall.empty()) f.why = too_tall + (f.why.empty() ? "" : "; " + f.why);
      f.within_tolerance = f.why.empty();
      out.push_back(std::move(f));
    }
  }
  std::sort(out.begin(), out.end(), [](const FeatureMeasure& a, const FeatureMeasure& b) { return a.id < b.id; });
  return out;
}

}  // namespace fairshape::feature
