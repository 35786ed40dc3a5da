#include "fairshape/feature/curve_placement.h"

#include <algorithm>
#include <cmath>

#include "fairshape/feature/geodesic_path.h"
#include "fairshape/feature/plane_section.h"
#include "fairshape/feature/polyline_import.h"

namespace fairshape::feature {
namespace {

std::string text(const Vec3& p) {
  return std::string("(") + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ", " + std::to_string(p.z()) + ")";
}

double mean_edge_length(const TriangleSurface& s) {
  double sum = 0;
  for (int f = 0; f < s.n_faces(); ++f)
    for (int i = 0; i < 3; ++i) sum += (s.vertex(s.corners(f)[(i + 1) % 3]) - s.vertex(s.corners(f)[i])).norm();
  return sum / (3.0 * std::max(1, s.n_faces()));
}

// "feature 'rim' (features[2].section.from)": the feature by name, the config key by path.
struct Where {
  std::string name, key;
  std::string operator()(const std::string& sub = "") const { return "feature '" + name + "' (" + key + sub + ")"; }
};

// Errors of the lower layers (a path, a file) carry no feature name: prefix it.
template <class F>
auto naming(const std::string& where, F&& f) {
  try {
    return f();
  } catch (const Error& e) {
    throw InvalidInput(where + ": " + e.what());
  }
}

SurfacePolyline reversed(SurfacePolyline line) {
  std::reverse(line.pieces.begin(), line.pieces.end());
  for (FacePiece& p : line.pieces) std::swap(p.from, p.to);
  return line;
}

std::vector<SurfacePoint> control_points(const TriangleSurface& s, const SurfacePolyline& line, double spacing,
                                         const std::vector<double>& keep, std::vector<char>* fixed) {
  if (spacing > 0) return resample(s, line, spacing, keep, fixed);
  return corner_points(line);
}

PlacedCurve place(const TriangleSurface& s, const GeodesicPlacement& g, bool closed, double max_distance,
                  const Where& where) {
  const std::vector<SurfacePoint> waypoints = points_on(s, g.through, max_distance, where(".through"));
  const GeodesicPath path = naming(where(), [&] { return geodesic_through(s, waypoints, closed); });
  // Smoothing needs evenly spaced points (the path's own corners bunch up near vertices).
  const double spacing = g.spacing > 0 ? g.spacing : g.smooth > 0 ? mean_edge_length(s) : 0.0;
  std::vector<char> fixed;
  PlacedCurve out{control_points(s, path.line, spacing, path.waypoint_arcs, &fixed), closed};
  if (g.smooth > 0) smooth_on_surface(s, out.points, closed, fixed, g.smooth);
  return out;
}

PlacedCurve place(const TriangleSurface& s, const SectionPlacement& c, double max_distance, const Where& where) {
  if (!(c.normal.norm() > 0) || !c.normal.allFinite() || !c.point.allFinite())
    throw InvalidInput(where(".normal") + ": the plane needs a finite point and a normal of nonzero length");
  const std::vector<SurfacePolyline> parts = plane_section(s, c.point, c.normal);
  if (parts.empty())
    throw InvalidInput(where() + ": the plane through " + text(c.point) + " with normal " + text(c.normal) +
                       " misses the surface of this level");
  // The component passing nearest to `nearest`.
  const Vec3 nearest = c.nearest.value_or(c.point);
  const auto distance_to = [&](const SurfacePolyline& line, const Vec3& x) {
    return (s.point(point_at_arc(s, line, closest_arc(s, line, x))) - x).norm();
  };
  const SurfacePolyline* chosen = &parts.front();
  for (const SurfacePolyline& line : parts)
    if (distance_to(line, nearest) < distance_to(*chosen, nearest)) chosen = &line;
  if (!c.from) return {control_points(s, *chosen, c.spacing, {}, nullptr), chosen->closed};
  // Clipped between the points of the section closest to `from` and `to`.
  for (const auto& [key, x] : {std::pair{"from", *c.from}, std::pair{"to", *c.to}})
    if (const double d = distance_to(*chosen, x); d > max_distance)
      throw InvalidInput(where(std::string(".") + key) + ": " + text(x) + " is " + std::to_string(d) +
                         " from the chosen section curve (at most " + std::to_string(max_distance) + " allowed)");
  const double total = polyline_length(s, *chosen);
  const double a = closest_arc(s, *chosen, *c.from), b = closest_arc(s, *chosen, *c.to);
  SurfacePolyline part;
  if (!chosen->closed) {
    part = a <= b ? between_arcs(s, *chosen, a, b) : reversed(between_arcs(s, *chosen, b, a));
  } else {
    const double forward = b >= a ? b - a : b - a + total;  // from → to in the loop's direction
    const bool go_forward = c.long_arc ? forward >= total - forward : forward <= total - forward;
    part = go_forward ? between_arcs(s, *chosen, a, a + forward) : reversed(between_arcs(s, *chosen, b, b + total - forward));
  }
  if (polyline_length(s, part) <= 1e-9 * total)
    throw InvalidInput(where() + ": from and to meet the section curve at the same point");
  return {control_points(s, part, c.spacing, {}, nullptr), false};
}

PlacedCurve place(const TriangleSurface& s, const PolylineFilePlacement& p, bool closed, double max_distance,
                  const Where& where) {
  const Polyline line = naming(where(), [&] { return read_curve_points(p.path); });
  return {project_to_surface(s, line.points, max_distance, where() + ", " + p.path), closed || line.closed};
}

}  // namespace

std::vector<SurfacePoint> points_on(const TriangleSurface& s, const PointsOnSurface& p, double max_distance,
                                    const std::string& where) {
  if (!p.world.empty()) {
    MatrixX3 m(static_cast<Eigen::Index>(p.world.size()), 3);
    for (std::size_t i = 0; i < p.world.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = p.world[i].transpose();
    return project_to_surface(s, m, max_distance, where);
  }
  for (std::size_t i = 0; i < p.surface.size(); ++i) {
    const SurfacePoint& q = p.surface[i];
    if (q.face < 0 || q.face >= s.n_faces())
      throw InvalidInput(where + "[" + std::to_string(i) + "]: face " + std::to_string(q.face) +
                         " is not a face of this level (0.." + std::to_string(s.n_faces() - 1) + ")");
  }
  return p.surface;
}

PlacedCurve place_curve(const TriangleSurface& s, const CurvePlacement& how, bool closed, double max_distance,
                        const std::string& feature, const std::string& key) {
  if (const auto* g = std::get_if<GeodesicPlacement>(&how))
    return place(s, *g, closed, max_distance, Where{feature, key + ".geodesic"});
  if (const auto* c = std::get_if<SectionPlacement>(&how)) return place(s, *c, max_distance, Where{feature, key + ".section"});
  return place(s, std::get<PolylineFilePlacement>(how), closed, max_distance, Where{feature, key + ".polyline"});
}

}  // namespace fairshape::feature
