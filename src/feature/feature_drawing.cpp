#include "fairshape/feature/feature_drawing.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fairshape/core/error.h"

namespace fairshape::feature {
namespace {

constexpr double kEdgesPerSide = 2;  // the fewest finest edges a side's radius must span
constexpr int kMostLevels = 8;       // input.levels' upper bound

double mean_edge(const SurfaceMesh& m, int f) {
  double sum = 0;
  int n = 0;
  int h = m.face_halfedge(f);
  const int first = h;
  do {
    sum += (m.position(m.to_vertex(h)) - m.position(m.from_vertex(h))).norm(), ++n;
    h = m.next(h);
  } while (h != first);
  return sum / n;
}

}  // namespace

void place_on_level(const TriangleSurface& s, double diagonal, FeatureDrawing& f) {
  if (f.placement) {  // a geodesic, a section or a file, on the level as it is before any feature
    PlacedCurve placed = place_curve(s, *f.placement, f.curve.closed, f.max_distance * diagonal, f.curve.name, f.key);
    f.curve.points = std::move(placed.points);
    f.curve.closed = placed.closed;
    return;
  }
  if (f.world_points.empty()) return;  // surface points, as given
  MatrixX3 P(static_cast<Eigen::Index>(f.world_points.size()), 3);
  for (std::size_t i = 0; i < f.world_points.size(); ++i) P.row(static_cast<Eigen::Index>(i)) = f.world_points[i].transpose();
  f.curve.points = project_to_surface(s, P, f.max_distance * diagonal, "feature '" + f.curve.name + "'");
}

double farthest_placed_point(const TriangleSurface& s, const FeatureDrawing& f) {
  double far = 0;
  if (f.placement || f.world_points.size() != f.curve.points.size()) return far;
  for (std::size_t i = 0; i < f.world_points.size(); ++i) far = std::max(far, (s.point(f.curve.points[i]) - f.world_points[i]).norm());
  return far;
}

double finest_edge_under(const FeatureCurve& curve, const SurfaceMesh& base, int levels) {
  if (curve.points.empty()) return 0;
  double sum = 0;
  for (const SurfacePoint& p : curve.points) {
    const long long ancestor = static_cast<long long>(p.face) >> (2 * curve.level);
    sum += mean_edge(base, static_cast<int>(ancestor));
  }
  return std::ldexp(sum / static_cast<double>(curve.points.size()), -levels);
}

void check_feature_width(const FeatureDrawing& f, const FeatureParams& q, const SurfaceMesh& base, int levels) {
  const double edge = finest_edge_under(f.curve, base, levels);
  if (!(edge > 0)) return;
  const double narrow = std::min(q.radius, q.right_radius());
  if (narrow >= kEdgesPerSide * edge) return;
  const int more = static_cast<int>(std::ceil(std::log2(kEdgesPerSide * edge / narrow)));
  std::ostringstream o;
  o.precision(3);
  o << f.key << ".radius: feature '" << f.curve.name << "' is narrower than " << kEdgesPerSide
    << " edges of its finest level: its " << (q.right_radius() < q.radius ? "right side's radius (radius / left_right_ratio) " : "radius ")
    << narrow << " against finest edges of about " << edge << " under the curve (level " << levels
    << "), which can neither show its profile nor measure it; give a radius of at least "
    << kEdgesPerSide * edge * std::max(1.0, q.left_right_ratio);
  if (levels + more <= kMostLevels) o << " or input.levels: " << levels + more << " (edges halve per level)";
  throw InvalidConfig(o.str());
}

}  // namespace fairshape::feature
