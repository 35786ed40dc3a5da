#include "fairshape/experiment/kinds/feature/feature_width_check.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "fairshape/core/error.h"

namespace fairshape {
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

double finest_edge_under(const feature::FeatureCurve& curve, const SurfaceMesh& base, int levels) {
  if (curve.points.empty()) return 0;
  double sum = 0;
  for (const feature::SurfacePoint& p : curve.points) {
    const long long ancestor = static_cast<long long>(p.face) >> (2 * curve.level);
    sum += mean_edge(base, static_cast<int>(ancestor));
  }
  return std::ldexp(sum / static_cast<double>(curve.points.size()), -levels);
}

void check_feature_width(const FeatureSpec& f, const SurfaceMesh& base, int levels) {
  const double edge = finest_edge_under(f.curve, base, levels);
  if (!(edge > 0)) return;
  std::vector<feature::FeatureParams> all{f.curve.params};
  for (const FeatureChange& c : f.changes) all.push_back(c.params);
  for (const feature::FeatureParams& q : all) {
    const double narrow = std::min(q.radius, q.right_radius());
    if (narrow >= kEdgesPerSide * edge) continue;
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
}

}  // namespace fairshape
