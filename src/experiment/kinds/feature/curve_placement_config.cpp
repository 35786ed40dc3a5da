#include "fairshape/experiment/kinds/feature/curve_placement_config.h"

#include <cmath>

#include "fairshape/experiment/kinds/feature/feature_run.h"
#include "fairshape/experiment/run_basics.h"

namespace fairshape {
namespace {

feature::PointsOnSurface read_waypoints(Config& g) {
  if (g.documenting()) {  // both forms' keys, neither given
    (void)read_point_list(g, "through", "waypoints as world points, projected onto the level");
    (void)read_surface_point_list(g, "through_surface", "waypoints as [face, b0, b1, b2] on the level");
    return {};
  }
  if (g.has("through") == g.has("through_surface"))
    throw InvalidConfig(g.path() + ": give exactly one of through ([[x, y, z], ...], projected onto the level) or "
                                   "through_surface ([[face, b0, b1, b2], ...])");
  feature::PointsOnSurface p;
  if (g.has("through")) p.world = read_point_list(g, "through", "waypoints as world points, projected onto the level");
  else p.surface = read_surface_point_list(g, "through_surface", "waypoints as [face, b0, b1, b2] on the level");
  if (p.size() < 2) throw InvalidConfig(g.path() + ": at least two waypoints");
  return p;
}

double read_spacing(Config& c) {
  return c.get_number("spacing", 0, 0, 1e12,
                      "control points about this far apart along the curve (world units); 0: the curve's own corners");
}

feature::GeodesicPlacement read_geodesic(Config& g) {
  feature::GeodesicPlacement out;
  out.through = read_waypoints(g);
  out.spacing = read_spacing(g);
  out.smooth = g.get_int("smooth", 0, 0, 1000, "umbrella smoothing steps on the surface (waypoints stay)");
  g.check_no_unknown_keys();
  return out;
}

feature::SectionPlacement read_section(Config& c) {
  feature::SectionPlacement out;
  const bool documenting = c.documenting();  // every key read, none given
  if ((!c.has("point") || !c.has("normal")) && !documenting) throw InvalidConfig(c.path() + ": the plane needs point and normal ([x, y, z] each)");
  out.point = read_vec3(c, "point", Vec3::Zero(), "a point of the plane");
  out.normal = read_vec3(c, "normal", Vec3::UnitZ(), "the plane's normal (any length > 0)");
  if (!(out.normal.norm() > 1e-12)) throw InvalidConfig(c.key_path("normal") + ": the normal has zero length");
  if (c.has("nearest") || documenting) out.nearest = read_vec3(c, "nearest", Vec3::Zero(), "picks the section curve passing nearest (default: point)");
  if (c.has("from") != c.has("to")) throw InvalidConfig(c.path() + ": give both from and to (clip the curve), or neither (the whole curve)");
  if (c.has("from") || documenting) {
    out.from = read_vec3(c, "from", Vec3::Zero(), "clip: the curve starts at its point closest to this");
    out.to = read_vec3(c, "to", Vec3::Zero(), "clip: the curve ends at its point closest to this");
  }
  out.long_arc = c.get_choice("arc", "short", {"short", "long"}, "a loop clipped by from/to: the shorter or the longer way") == "long";
  if (c.has("arc") && !c.has("from")) throw InvalidConfig(c.key_path("arc") + ": only with from and to");
  out.spacing = read_spacing(c);
  c.check_no_unknown_keys();
  return out;
}

}  // namespace

std::vector<Vec3> read_point_list(Config& c, const std::string& key, const std::string& doc) {
  const auto rows = c.get<std::vector<std::vector<double>>>(key, {}, doc);
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].size() != 3) throw InvalidConfig(c.key_path(key) + "[" + std::to_string(i) + "]: expected [x, y, z]");
    out.emplace_back(rows[i][0], rows[i][1], rows[i][2]);
  }
  return out;
}

std::vector<feature::SurfacePoint> read_surface_point_list(Config& c, const std::string& key, const std::string& doc) {
  const auto rows = c.get<std::vector<std::vector<double>>>(key, {}, doc);
  std::vector<feature::SurfacePoint> out;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::string w = c.key_path(key) + "[" + std::to_string(i) + "]";
    if (rows[i].size() != 4 || rows[i][0] != std::floor(rows[i][0]) || rows[i][0] < 0 || rows[i][0] > 1e9)
      throw InvalidConfig(w + ": expected [face, b0, b1, b2] with a face index >= 0");
    feature::SurfacePoint p{static_cast<int>(rows[i][0]), Vec3(rows[i][1], rows[i][2], rows[i][3])};
    if (p.bary.minCoeff() < 0 || std::abs(p.bary.sum() - 1) > 1e-9)
      throw InvalidConfig(w + ": barycentric coordinates must be >= 0 and sum to 1");
    out.push_back(p);
  }
  return out;
}

int curve_keys_given(const Config& f) {
  int n = 0;
  for (const char* key : {"points", "surface_points", "geodesic", "section", "polyline"}) n += f.has(key) ? 1 : 0;
  return n;
}

std::optional<feature::CurvePlacement> read_curve_placement(Config& f, const std::vector<std::string>& dirs) {
  for (const char* key : {"geodesic", "section"})
    if (f.has(key) && !f.node()[key].IsMap()) throw InvalidConfig(f.key_path(key) + ": expected a map {...}");
  if (f.has("geodesic")) {
    Config g = f.child("geodesic", "a shortest path on the level through waypoints: {through | through_surface, spacing, smooth}");
    return read_geodesic(g);
  }
  if (f.has("section")) {
    Config c = f.child("section", "the level cut by a plane: {point, normal, nearest, from, to, arc, spacing}");
    return read_section(c);
  }
  if (f.has("polyline")) {
    const std::string path = f.require<std::string>("polyline", "a file of points: .obj polyline or 'x y z' lines");
    return feature::PolylineFilePlacement{resolve_input(path, dirs, f.key_path("polyline"))};
  }
  return std::nullopt;
}

// Where the feature's control polygon comes from (one of five keys) and whether it is closed.
void read_curve_source(Config& c, const std::string& where, const std::vector<std::string>& dirs,
                       feature::FeatureDrawing& f) {
  if (c.documenting()) {  // the keys of every source, none of them given
    (void)c.get<bool>("closed", false, "the curve closes on itself: no ends, no end caps, a periodic spline");
    (void)read_point_list(c, "points", "world points, projected onto the level's surface");
    (void)read_surface_point_list(c, "surface_points", "points as [face, b0, b1, b2] on the level");
    Config g = c.child("geodesic", "a shortest path on the level through waypoints: {through | through_surface, spacing, smooth}");
    (void)read_geodesic(g);
    Config section = c.child("section", "the level cut by a plane: {point, normal, nearest, from, to, arc, spacing}");
    (void)read_section(section);
    (void)c.get<std::string>("polyline", "", "a file of points: .obj polyline or 'x y z' lines");
    return;
  }
  if (curve_keys_given(c) != 1)
    throw InvalidConfig(where + ": give exactly one of points ([[x, y, z], ...], projected onto the level), "
                                "surface_points ([[face, b0, b1, b2], ...]), geodesic, section or polyline");
  f.curve.closed = c.get<bool>("closed", false, "the curve closes on itself: no ends, no end caps, a periodic spline");
  f.placement = read_curve_placement(c, dirs);
  if (c.has("points")) f.world_points = read_point_list(c, "points", "world points, projected onto the level's surface");
  if (c.has("surface_points")) f.curve.points = read_surface_point_list(c, "surface_points", "points as [face, b0, b1, b2] on the level");
  const std::size_t given = f.world_points.size() + f.curve.points.size();
  if (!f.placement && given < (f.curve.closed ? 3u : 2u))
    throw InvalidConfig(f.curve.closed ? c.key_path("closed") + ": a closed curve needs at least three points"
                                       : where + ": at least two points");
  if (f.curve.closed && f.placement && std::holds_alternative<feature::SectionPlacement>(*f.placement))
    throw InvalidConfig(c.key_path("closed") + ": a section is closed when taken whole around a loop (no from/to); "
                                               "leave closed out");
  if (f.curve.closed && f.placement && std::holds_alternative<feature::GeodesicPlacement>(*f.placement) &&
      std::get<feature::GeodesicPlacement>(*f.placement).through.size() < 3)
    throw InvalidConfig(c.key_path("closed") + ": a closed geodesic needs at least three waypoints");
  if (f.curve.closed && f.curve.params.end_height_ratio != 1.0)
    throw InvalidConfig(c.key_path("end_height_ratio") + ": " + std::to_string(f.curve.params.end_height_ratio) +
                        " on a closed curve (the height would jump at the seam; only 1 is allowed)");
}

}  // namespace fairshape
