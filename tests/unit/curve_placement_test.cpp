// Placing feature curves on the surface (feature/curve_placement.h): geodesics through waypoints,
// plane sections, closed curves without a seam, polylines from files, and the errors for bad
// placements (different components, a plane that misses, too few points), through the library
// and through a run's config.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <numbers>
#include <queue>

#include "fairshape/experiment/kinds/feature/feature_run.h"
#include "fairshape/experiment/run_basics.h"
#include "fairshape/feature/curve_placement.h"
#include "fairshape/feature/geodesic_path.h"
#include "fairshape/feature/perturbation.h"
#include "fairshape/feature/plane_section.h"
#include "fairshape/feature/polyline_import.h"
#include "fairshape/io/mesh_io.h"
#include "feature_test_meshes.h"
#include "fairshape/remesh/closest_point.h"
#include "test_support.h"

using namespace fairshape;
using namespace fairshape::feature;
using fairshape::test::cylinder;

namespace {

// A triangulated n × n grid on [x0, x0 + size] × [0, size] in the plane z = 0.
void add_plane_grid(int n, double size, double x0, std::vector<Vec3>& V, PolygonList& faces) {
  const int base = static_cast<int>(V.size());
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) V.emplace_back(x0 + size * i / n, size * j / n, 0.0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = base + j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      faces.push_back({a, b, d});
      faces.push_back({a, d, c});
    }
}

SurfaceMesh mesh_of(const std::vector<Vec3>& V, const PolygonList& faces) {
  MatrixX3 P(static_cast<Eigen::Index>(V.size()), 3);
  for (std::size_t i = 0; i < V.size(); ++i) P.row(static_cast<Eigen::Index>(i)) = V[i].transpose();
  return SurfaceMesh::from_polygons(P, faces);
}

SurfaceMesh plane_grid(int n, double size) {
  std::vector<Vec3> V;
  PolygonList faces;
  add_plane_grid(n, size, 0.0, V, faces);
  return mesh_of(V, faces);
}

// A torus around z: tube radius r, centre-line radius R, n × m vertices.
SurfaceMesh torus(int n, int m, double R, double r) {
  std::vector<Vec3> V;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * std::numbers::pi * i / n, v = 2 * std::numbers::pi * j / m;
      V.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  PolygonList faces;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const int a = i * m + j, b = ((i + 1) % n) * m + j, c = i * m + (j + 1) % m, d = ((i + 1) % n) * m + (j + 1) % m;
      faces.push_back({a, b, d});
      faces.push_back({a, d, c});
    }
  return mesh_of(V, faces);
}

// A disc of radius 1 in z = 0 on a polar grid: a centre, `rings` rings of `sectors` vertices. The
// mesh is symmetric under a rotation by one sector.
SurfaceMesh polar_disc(int rings, int sectors) {
  std::vector<Vec3> V{Vec3::Zero()};
  for (int j = 1; j <= rings; ++j)
    for (int i = 0; i < sectors; ++i) {
      const double a = 2 * std::numbers::pi * i / sectors, rho = static_cast<double>(j) / rings;
      V.emplace_back(rho * std::cos(a), rho * std::sin(a), 0.0);
    }
  const auto at = [&](int j, int i) { return 1 + (j - 1) * sectors + (i % sectors); };
  PolygonList faces;
  for (int i = 0; i < sectors; ++i) faces.push_back({0, at(1, i), at(1, i + 1)});
  for (int j = 1; j < rings; ++j)
    for (int i = 0; i < sectors; ++i) {
      faces.push_back({at(j, i), at(j + 1, i + 1), at(j, i + 1)});
      faces.push_back({at(j, i), at(j + 1, i), at(j + 1, i + 1)});
    }
  return mesh_of(V, faces);
}

MatrixX3 up_normals(const SurfaceMesh& m) {
  MatrixX3 n(m.n_vertices(), 3);
  n.rowwise() = Eigen::RowVector3d(0, 0, 1);
  return n;
}

SurfacePoint at_vertex(const TriangleSurface& s, int v) {
  for (int f = 0; f < s.n_faces(); ++f)
    if (const int c = s.corner_of(f, v); c >= 0) return {f, Vec3::Unit(c)};
  FAIL("vertex " << v << " has no face");
  return {};
}

SurfacePoint on_surface(const TriangleSurface& s, const Vec3& x) {
  return project_to_surface(s, MatrixX3(x.transpose()), 1e-3, "test point")[0];
}

// Length of the shortest path along mesh edges (Dijkstra): one of the paths a geodesic must beat.
double edge_path_length(const SurfaceMesh& m, int from, int to) {
  std::vector<double> dist(static_cast<std::size_t>(m.n_vertices()), std::numeric_limits<double>::infinity());
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  dist[static_cast<std::size_t>(from)] = 0;
  queue.push({0, from});
  while (!queue.empty()) {
    const double d = queue.top().first;  // named copies: the lambda below captures them (clang)
    const int v = queue.top().second;
    queue.pop();
    if (v == to) return d;
    if (d > dist[static_cast<std::size_t>(v)]) continue;
    m.for_each_outgoing(v, [&](int h) {
      const int w = m.to_vertex(h);
      const double nd = d + (m.position(w) - m.position(v)).norm();
      if (nd < dist[static_cast<std::size_t>(w)]) dist[static_cast<std::size_t>(w)] = nd, queue.push({nd, w});
    });
  }
  return std::numeric_limits<double>::infinity();
}

// Largest distance of the polyline's corners from the mesh (an independent AABB query), and
// largest gap between one piece's end and the next one's start.
std::pair<double, double> off_surface_and_gaps(const TriangleSurface& s, const SurfacePolyline& line) {
  const ClosestPointQuery mesh(s.mesh());
  double off = 0, gap = 0;
  for (std::size_t k = 0; k < line.pieces.size(); ++k) {
    const FacePiece& p = line.pieces[k];
    CHECK(p.from.minCoeff() >= -1e-12);
    CHECK(p.to.minCoeff() >= -1e-12);
    CHECK(std::abs(p.from.sum() - 1) < 1e-12);
    const Vec3 a = s.point({p.face, p.from});
    off = std::max(off, (mesh.closest_points(MatrixX3(a.transpose())).row(0).transpose() - a).norm());
    const std::size_t next = k + 1 < line.pieces.size() ? k + 1 : line.closed ? 0 : k;
    if (next != k) {
      const FacePiece& q = line.pieces[next];
      gap = std::max(gap, (s.point({p.face, p.to}) - s.point({q.face, q.from})).norm());
    }
  }
  return {off, gap};
}

// Signed area of the polyline's corners projected to the xy plane (> 0: counter-clockwise).
double signed_area_xy(const TriangleSurface& s, const SurfacePolyline& line) {
  double a = 0;
  for (const FacePiece& p : line.pieces) {
    const Vec3 x = s.point({p.face, p.from}), y = s.point({p.face, p.to});
    a += 0.5 * (x.x() * y.y() - y.x() * x.y());
  }
  return a;
}

}  // namespace

TEST_CASE("geodesics through waypoints: no longer than edge paths, no shorter than the straight line, on the surface",
          "[feature][placement]") {
  const SurfaceMesh knot = read_mesh(test::data_path("knot.off"));
  const TriangleSurface s(knot, loop_limit_normals(knot));
  const std::vector<int> via{12, 700, 1451};
  std::vector<SurfacePoint> waypoints;
  for (int v : via) waypoints.push_back(at_vertex(s, v));
  const GeodesicPath path = geodesic_through(s, waypoints, false);
  REQUIRE(path.waypoint_arcs.size() == 3);
  const std::vector<double> lengths = piece_lengths(s, path.line);
  double edge_paths = 0, straight = 0;
  for (std::size_t k = 0; k + 1 < via.size(); ++k) {
    edge_paths += edge_path_length(knot, via[k], via[k + 1]);
    straight += (knot.position(via[k + 1]) - knot.position(via[k])).norm();
    // Each leg on its own: between its waypoints' arcs.
    const double leg = path.waypoint_arcs[k + 1] - path.waypoint_arcs[k];
    CHECK(leg <= edge_path_length(knot, via[k], via[k + 1]) + 1e-9);
    CHECK(leg >= (knot.position(via[k + 1]) - knot.position(via[k])).norm() - 1e-9);
  }
  const double length = polyline_length(s, path.line);
  INFO("geodesic " << length << ", edge paths " << edge_paths << ", straight " << straight);
  CHECK(length <= edge_paths);
  CHECK(length < 0.99 * edge_paths);  // strictly shorter: it cuts across faces
  CHECK(length >= straight);
  const auto [off, gap] = off_surface_and_gaps(s, path.line);
  CHECK(off < 1e-9);
  CHECK(gap < 1e-12);
  for (std::size_t k = 0; k < via.size(); ++k)
    CHECK((s.point(point_at_arc(s, path.line, path.waypoint_arcs[k])) - knot.position(via[k])).norm() < 1e-9);

  // On a flat grid the geodesic is the straight segment; on a cylinder it unrolls to one.
  const SurfaceMesh plane = plane_grid(16, 1.0);
  const TriangleSurface flat(plane, up_normals(plane));
  const Vec3 a(0.13, 0.21, 0), b(0.87, 0.66, 0);
  const GeodesicPath line = geodesic_through(flat, {on_surface(flat, a), on_surface(flat, b)}, false);
  CHECK(polyline_length(flat, line.line) == Approx((b - a).norm()).epsilon(1e-12));
  const int around = 24;
  const SurfaceMesh cyl = cylinder(around, 6, 1.0, 3.0);
  const TriangleSurface round(cyl, loop_limit_normals(cyl));
  const int v0 = around + 1, v1 = 5 * around + 6;  // 5 sectors around, 4 rings up
  const double chord = 2 * std::sin(std::numbers::pi / around);
  const GeodesicPath helix = geodesic_through(round, {at_vertex(round, v0), at_vertex(round, v1)}, false);
  CHECK(polyline_length(round, helix.line) == Approx(std::hypot(5 * chord, 2.0)).epsilon(1e-9));
}

TEST_CASE("geodesic placement: a closed path returns to its first waypoint, spacing and smoothing keep the waypoints",
          "[feature][placement]") {
  const SurfaceMesh knot = read_mesh(test::data_path("knot.off"));
  const TriangleSurface s(knot, loop_limit_normals(knot));
  GeodesicPlacement g;
  for (int v : {100, 600, 1300}) g.through.surface.push_back(at_vertex(s, v));
  const PlacedCurve closed = place_curve(s, g, true, 1.0, "loop", "features[0]");
  CHECK(closed.closed);
  CHECK(closed.points.size() > 10);
  const PlacedCurve open = place_curve(s, g, false, 1.0, "path", "features[0]");
  CHECK(!open.closed);
  CHECK((s.point(open.points.front()) - knot.position(100)).norm() < 1e-12);
  CHECK((s.point(open.points.back()) - knot.position(1300)).norm() < 1e-12);
  // Resampled and smoothed: the waypoints are still samples, and the points are ~spacing apart.
  g.spacing = 0.02;
  g.smooth = 5;
  const PlacedCurve smooth = place_curve(s, g, false, 1.0, "path", "features[0]");
  for (int v : {100, 600, 1300}) {
    double nearest = 1e9;
    for (const SurfacePoint& p : smooth.points) nearest = std::min(nearest, (s.point(p) - knot.position(v)).norm());
    CHECK(nearest < 1e-9);
  }
  const ClosestPointQuery mesh(knot);
  for (std::size_t k = 1; k < smooth.points.size(); ++k) {
    const Vec3 p = s.point(smooth.points[k]);
    CHECK((p - s.point(smooth.points[k - 1])).norm() < 2 * g.spacing);
    CHECK((mesh.closest_points(MatrixX3(p.transpose())).row(0).transpose() - p).norm() < 1e-9);
  }
}

TEST_CASE("plane sections lie on the plane and the surface, loops are closed and oriented by the normals",
          "[feature][placement]") {
  const double R = 1.0, r = 0.3;
  const SurfaceMesh ring = torus(48, 16, R, r);
  const TriangleSurface s(ring, loop_limit_normals(ring));
  const Vec3 point(0.1, -0.2, 0.05), normal(0, 0, 2);
  const std::vector<SurfacePolyline> parts = plane_section(s, point, normal);
  REQUIRE(parts.size() == 2);  // the inner and the outer circle of the torus
  for (const SurfacePolyline& line : parts) {
    CHECK(line.closed);
    for (const FacePiece& p : line.pieces)
      for (const Vec3& w : {p.from, p.to}) CHECK(std::abs((s.point({p.face, w}) - point).dot(normal.normalized())) < 1e-12);
    const auto [off, gap] = off_surface_and_gaps(s, line);
    CHECK(off < 1e-9);
    CHECK(gap < 1e-12);
  }
  // Both circles, each within the facets' sag of its radius; each runs along normal × (outward
  // surface normal): counter-clockwise about +z outside, clockwise around the hole.
  const bool outer_first = polyline_length(s, parts[0]) > polyline_length(s, parts[1]);
  const SurfacePolyline& outside = parts[outer_first ? 0 : 1];
  const SurfacePolyline& inside = parts[outer_first ? 1 : 0];
  CHECK(signed_area_xy(s, outside) > 0);
  CHECK(signed_area_xy(s, inside) < 0);
  const std::vector<double> lengths{polyline_length(s, inside), polyline_length(s, outside)};
  const double z = 0.05, half_width = std::sqrt(r * r - z * z);
  CHECK(lengths[0] == Approx(2 * std::numbers::pi * (R - half_width)).epsilon(0.02));
  CHECK(lengths[1] == Approx(2 * std::numbers::pi * (R + half_width)).epsilon(0.02));

  // Placement: the component nearest a point, whole (closed) or clipped the short or long way.
  SectionPlacement c;
  c.point = point;
  c.normal = normal;
  c.nearest = Vec3(R + r, 0, 0);
  const PlacedCurve outer = place_curve(s, c, false, 0.1, "rim", "features[0]");
  CHECK(outer.closed);
  for (const SurfacePoint& p : outer.points) CHECK(s.point(p).head<2>().norm() > R);
  c.from = Vec3(R + r, 0, 0);
  c.to = Vec3(0, R + r, 0);
  const PlacedCurve quarter = place_curve(s, c, false, 0.1, "rim", "features[0]");
  c.long_arc = true;
  const PlacedCurve three_quarters = place_curve(s, c, false, 0.1, "rim", "features[0]");
  CHECK(!quarter.closed);
  const auto arc_length = [&](const PlacedCurve& pc) {
    double l = 0;
    for (std::size_t k = 1; k < pc.points.size(); ++k) l += (s.point(pc.points[k]) - s.point(pc.points[k - 1])).norm();
    return l;
  };
  CHECK(arc_length(quarter) == Approx(0.25 * lengths[1]).epsilon(0.03));
  CHECK(arc_length(three_quarters) == Approx(0.75 * lengths[1]).epsilon(0.03));
  CHECK(s.point(quarter.points.front()).x() > R);  // runs from `from` to `to`
  CHECK(s.point(quarter.points.back()).y() > R);
  CHECK(s.point(three_quarters.points.front()).x() > R);

  // A section of a surface with a boundary runs from boundary to boundary.
  const SurfaceMesh plane = plane_grid(8, 1.0);
  const TriangleSurface flat(plane, up_normals(plane));
  const std::vector<SurfacePolyline> cut = plane_section(flat, Vec3(0.4, 0.5, 0), Vec3(1, 1, 0));
  REQUIRE(cut.size() == 1);
  CHECK(!cut[0].closed);
  CHECK(polyline_length(flat, cut[0]) == Approx(0.9 * std::sqrt(2.0)).epsilon(1e-12));
}

TEST_CASE("a closed feature curve has no seam: the displacement at the seam matches the rest of the circle",
          "[feature][placement]") {
  // A 12-gon around the centre of a polar disc of 48 sectors: the curve, the mesh and so the
  // displacement repeat every 4 sectors. The periodic spline starts (its seam) halfway between
  // the last and the first control point, at sector 46; the open one ends at sector 0.
  const int rings = 24, sectors = 48;
  const SurfaceMesh disc = polar_disc(rings, sectors);
  const TriangleSurface flat(disc, up_normals(disc));
  std::vector<Vec3> circle;
  for (int k = 0; k < 12; ++k) {
    const double a = 2 * std::numbers::pi * k / 12;
    circle.emplace_back(0.5 * std::cos(a), 0.5 * std::sin(a), 0.0);
  }
  FeatureParams q;
  q.radius = 0.15;
  q.height = 0.02;
  q.quadratic = true;
  const auto points_of = [&](const std::vector<Vec3>& xs) {
    MatrixX3 m(static_cast<Eigen::Index>(xs.size()), 3);
    for (std::size_t i = 0; i < xs.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = xs[i].transpose();
    return project_to_surface(flat, m, 1e-9, "circle");
  };
  // Largest difference between the displacement at any vertex and at the 11 vertices the
  // symmetry maps it to (every ring, every sector): a seam anywhere breaks it.
  const auto seam_mismatch = [&](const FeatureCurve& curve) {
    const MatrixX3 d = compute_perturbation(flat, {build_base_curve(flat, curve)}, Backend::Optimized).dense(disc.n_vertices());
    double worst = 0, largest = 0;
    for (int j = 1; j <= rings; ++j) {
      const auto at = [&](int i) { return 1 + (j - 1) * sectors + (i % sectors); };
      for (int i = 0; i < 4; ++i) {
        largest = std::max(largest, std::abs(d(at(i), 2)));
        for (int k = 1; k < 12; ++k) worst = std::max(worst, std::abs(d(at(i + 4 * k), 2) - d(at(i), 2)));
      }
    }
    CHECK(largest > 0.5 * q.height);  // the ring next to the curve is raised
    return worst;
  };
  const double closed = seam_mismatch(FeatureCurve{"loop", 0, points_of(circle), q, true});
  // The same circle drawn open, ending just short of its start (a repeated point is refused):
  // two end caps and a corner at the seam.
  std::vector<Vec3> open_circle = circle;
  open_circle.push_back(Vec3(0.5 * std::cos(-0.01), 0.5 * std::sin(-0.01), 0.0));
  const double open = seam_mismatch(FeatureCurve{"teardrop", 0, points_of(open_circle), q, false});
  INFO("seam mismatch: closed " << closed << ", open " << open);
  CHECK(closed < 1e-9 * q.height);
  CHECK(open > 1e-2 * q.height);
  // A base curve around a closed curve links its last segment to its first.
  const BaseCurve base = build_base_curve(flat, FeatureCurve{"loop", 0, points_of(circle), q, true});
  CHECK(base.closed);
  CHECK(base.segments.front().prev == static_cast<int>(base.segments.size()) - 1);
  CHECK(base.segments.back().next == 0);
  CHECK((base.segments.back().b - base.segments.front().a).norm() < 1e-12);
}

TEST_CASE("a section around a cylinder as a closed feature moves every vertex of a ring alike", "[feature][placement]") {
  const int around = 32;
  const SurfaceMesh cyl = cylinder(around, 8, 1.0, 4.0);
  const TriangleSurface s(cyl, loop_limit_normals(cyl));
  SectionPlacement c;
  c.point = Vec3(0, 0, 2.2);
  c.normal = Vec3(0, 0, 1);
  const PlacedCurve ring = place_curve(s, c, false, 0.01, "belt", "features[0]");
  REQUIRE(ring.closed);
  FeatureParams q;
  q.radius = 0.4;
  q.height = 0.03;
  q.quadratic = true;
  const MatrixX3 d =
      compute_perturbation(s, {build_base_curve(s, FeatureCurve{"belt", 0, ring.points, q, true})}, Backend::Optimized)
          .dense(cyl.n_vertices());
  for (int j : {4, 5}) {  // the rings at z = 2 and z = 2.5, either side of the belt
    double lo = 1e9, hi = 0;
    for (int i = 0; i < around; ++i) {
      const double n = d.row(j * around + i).norm();
      lo = std::min(lo, n), hi = std::max(hi, n);
    }
    INFO("ring " << j << ": displacement from " << lo << " to " << hi);
    CHECK(lo > 0.1 * q.height);
    CHECK(hi - lo < 1e-9 * q.height);
  }
}

TEST_CASE("curves from polyline files: obj and point lists, closed when they end where they began",
          "[feature][placement]") {
  const auto dir = test::scratch_dir("curve_placement_files");
  const std::string txt = (dir / "curve.txt").string(), loop = (dir / "loop.xyz").string(), obj = (dir / "curve.obj").string(),
                    bad = (dir / "bad.txt").string();
  std::ofstream(txt) << "# a curve\n0.1 0.2 0\n0.5 0.5 0.01\n\n0.9 0.4 0\n";
  std::ofstream(loop) << "0.2 0.2 0\n0.8 0.2 0\n0.8 0.8 0\n0.2 0.8 0\n0.2 0.2 0\n";
  std::ofstream(obj) << "v 0.1 0.1 0\nv 0.5 0.9 0\nv 0.9 0.1 0\nl 1 2 3\n";
  std::ofstream(bad) << "0.1 0.2 0\n0.5 0.5\n";
  const Polyline a = read_curve_points(txt);
  CHECK(a.n_points() == 3);
  CHECK(!a.closed);
  CHECK(a.points(1, 2) == 0.01);
  const Polyline b = read_curve_points(loop);
  CHECK(b.n_points() == 4);
  CHECK(b.closed);
  CHECK(read_curve_points(obj).n_points() == 3);
  CHECK_THROWS_WITH(read_curve_points(bad), Catch::Contains("bad.txt") && Catch::Contains("2"));

  const SurfaceMesh plane = plane_grid(8, 1.0);
  const TriangleSurface flat(plane, up_normals(plane));
  const PlacedCurve placed = place_curve(flat, PolylineFilePlacement{loop}, false, 0.05, "square", "features[1]");
  CHECK(placed.closed);
  CHECK(placed.points.size() == 4);
  CHECK_THROWS_WITH(place_curve(flat, PolylineFilePlacement{txt}, false, 0.001, "lifted", "features[1]"),
                    Catch::Contains("feature 'lifted' (features[1].polyline)") && Catch::Contains("leaves the surface"));
}

TEST_CASE("bad placements: different components, a plane that misses, too few points, a repeated first point",
          "[feature][placement]") {
  std::vector<Vec3> V;
  PolygonList faces;
  add_plane_grid(4, 1.0, 0.0, V, faces);
  add_plane_grid(4, 1.0, 2.0, V, faces);
  const SurfaceMesh two = mesh_of(V, faces);
  const TriangleSurface s(two, up_normals(two));
  CHECK(face_components(s) != std::vector<int>(static_cast<std::size_t>(s.n_faces()), 0));
  GeodesicPlacement g;
  g.through.world = {Vec3(0.5, 0.5, 0), Vec3(0.7, 0.2, 0), Vec3(2.5, 0.5, 0)};
  CHECK_THROWS_WITH(place_curve(s, g, false, 0.01, "bridge", "features[2]"),
                    Catch::Contains("feature 'bridge' (features[2].geodesic)") && Catch::Contains("waypoint 2") &&
                        Catch::Contains("different connected component"));
  SectionPlacement c;
  c.point = Vec3(0, 0, 1);
  c.normal = Vec3(0, 0, 1);
  CHECK_THROWS_WITH(place_curve(s, c, false, 0.01, "rim", "features[0]"),
                    Catch::Contains("feature 'rim' (features[0].section)") && Catch::Contains("misses the surface"));
  c.point = Vec3(0.5, 0.5, 0);
  c.normal = Vec3(1, 0, 0);
  c.from = Vec3(0.5, 0.2, 0);
  c.to = Vec3(0.5, 0.2, 0);
  CHECK_THROWS_WITH(place_curve(s, c, false, 0.01, "rim", "features[0]"), Catch::Contains("same point"));
  c.to = Vec3(0.5, 0.8, 0.5);
  CHECK_THROWS_WITH(place_curve(s, c, false, 0.01, "rim", "features[0]"), Catch::Contains("features[0].section.to"));

  FeatureParams q;
  const std::vector<SurfacePoint> two_points{on_surface(s, Vec3(0.2, 0.2, 0)), on_surface(s, Vec3(0.8, 0.3, 0))};
  CHECK_THROWS_WITH(build_base_curve(s, FeatureCurve{"loop", 0, two_points, q, true}),
                    Catch::Contains("feature 'loop'") && Catch::Contains("at least 3 points"));
  std::vector<SurfacePoint> back = two_points;
  back.push_back(on_surface(s, Vec3(0.5, 0.8, 0)));
  back.push_back(two_points.front());
  CHECK_THROWS_WITH(build_base_curve(s, FeatureCurve{"teardrop", 0, back, q, false}), Catch::Contains("closed: true"));
  back.pop_back();
  q.end_height_ratio = 0.5;
  CHECK_THROWS_WITH(build_base_curve(s, FeatureCurve{"fading", 0, back, q, true}), Catch::Contains("end_height_ratio"));
  q.end_height_ratio = 1;
  CHECK_NOTHROW(build_base_curve(s, FeatureCurve{"loop", 0, back, q, true}));
}

TEST_CASE("placement keys in a feature config: checked at load, errors name the feature and the key",
          "[feature][placement]") {
  const std::vector<std::string> dirs = input_search_dirs(test::source_path("configs/khodakovsky-schroder/fig11.yaml"));
  const auto spec = [&](const std::string& feature) {
    return FeatureRunSpec::from_config(YAML::Load("{name: t, input: {mesh: data/ks_patch.off, levels: 2}, "
                                                  "feature_defaults: {radius: 0.1, height: 0.02}, features: [" +
                                                  feature + "]}"),
                                       dirs);
  };
  CHECK_NOTHROW(spec("{name: g, geodesic: {through: [[-0.5, -0.5, 0.03], [0.5, 0.2, 0.02]], spacing: 0.05, smooth: 3}}"));
  CHECK_NOTHROW(spec("{name: s, section: {point: [0, 0, 0], normal: [1, 0, 0], from: [0, -0.6, 0], to: [0, 0.6, 0]}}"));
  CHECK_THROWS_WITH(spec("{name: g, geodesic: {throuhg: [[0, 0, 0], [0.5, 0, 0]]}}"),
                    Catch::Contains("features[0].geodesic"));
  CHECK_THROWS_WITH(spec("{name: g, geodesic: {through: [[0, 0, 0], [0.5, 0, 0]], spacing: -1}}"),
                    Catch::Contains("features[0].geodesic.spacing"));
  CHECK_THROWS_WITH(spec("{name: g, geodesic: {through: [[0, 0, 0], [0.5, 0, .nan]]}}"),
                    Catch::Contains("features[0].geodesic.through"));
  CHECK_THROWS_WITH(spec("{name: g, geodesic: {through: [[0, 0, 0]]}}"), Catch::Contains("at least two waypoints"));
  CHECK_THROWS_WITH(spec("{name: s, section: {point: [0, 0, 0], normal: [0, 0, 0]}}"),
                    Catch::Contains("features[0].section.normal"));
  CHECK_THROWS_WITH(spec("{name: s, section: {point: [0, 0, 0], normal: [1, 0, 0], from: [0, 0, 0]}}"),
                    Catch::Contains("both from and to"));
  CHECK_THROWS_WITH(spec("{name: s, section: {point: [0, 0, 0], normal: [1, 0, 0]}, closed: true}"),
                    Catch::Contains("features[0].closed"));
  CHECK_THROWS_WITH(spec("{name: c, closed: true, points: [[0, 0, 0], [0.5, 0, 0]]}"),
                    Catch::Contains("features[0].closed") && Catch::Contains("three points"));
  CHECK_THROWS_WITH(spec("{name: c, closed: true, end_height_ratio: 0, points: [[0, 0, 0], [0.5, 0, 0], [0, 0.5, 0]]}"),
                    Catch::Contains("features[0].end_height_ratio"));
  CHECK_THROWS_WITH(spec("{name: p, points: [[0, 0, 0], [0.5, 0, 0]], geodesic: {through: [[0, 0, 0], [0.5, 0, 0]]}}"),
                    Catch::Contains("give exactly one of"));
  CHECK_THROWS_WITH(spec("{name: f, polyline: no/such/file.obj}"), Catch::Contains("features[0].polyline"));

  // Errors only the level can show come from placing the features, naming feature and key (two
  // levels: at one the radius would span about one finest edge, refused as too narrow).
  FeatureRunSpec miss = spec("{name: rim, section: {point: [0, 0, 5], normal: [0, 0, 1]}}");
  CHECK_THROWS_WITH(placed_features(miss, feature_hierarchy(miss)),
                    Catch::Contains("feature 'rim' (features[0].section)") && Catch::Contains("misses the surface"));
  FeatureRunSpec ok = spec("{name: rim, section: {point: [0, 0, 0], normal: [1, 0.2, 0]}}");
  const std::unique_ptr<FeatureSession> placed = placed_features(ok, feature_hierarchy(ok));
  CHECK(placed->features().at(0).points.size() > 5);
  CHECK_NOTHROW(placed->check_coarsest_features());
}
