// CGAL's exact geodesics (the Chen-Han style window propagation of Surface_mesh_shortest_path)
// on a copy of the part of the level a leg can pass through. CGAL propagates from the source
// over every face it is given, far beyond the target (on level 3 of the helmet, 64,000 faces, a
// leg took ~20 s), so each leg gets only the faces within the ellipsoid its geodesic cannot
// leave: every point x of a path of length ≤ L from a to b has |x − a| + |x − b| ≤ L, and L is
// bounded by a path along the edges. The result is the same geodesic, exactly.
#include "fairshape/feature/geodesic_path.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>

#include <algorithm>
#include <array>
#include <functional>
#include <numeric>
#include <optional>
#include <queue>

namespace fairshape::feature {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Traits = CGAL::Surface_mesh_shortest_path_traits<Kernel, Mesh>;
using ShortestPath = CGAL::Surface_mesh_shortest_path<Traits>;

// A length no geodesic from `from` to `to` exceeds: straight to a corner of its face, along
// edges (Dijkstra), straight from a corner of the target's face. Infinite when not connected.
double edge_path_bound(const TriangleSurface& s, const SurfacePoint& from, const SurfacePoint& to) {
  const SurfaceMesh& m = s.mesh();
  std::vector<double> dist(static_cast<std::size_t>(m.n_vertices()), std::numeric_limits<double>::infinity());
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  for (int c : s.corners(from.face)) {
    dist[static_cast<std::size_t>(c)] = (s.vertex(c) - s.point(from)).norm();
    queue.push({dist[static_cast<std::size_t>(c)], c});
  }
  const auto& targets = s.corners(to.face);
  int settled = 0;
  while (!queue.empty() && settled < 3) {
    // Named copies, not a structured binding: the lambda below captures them (clang, used by
    // the ASan build, refuses to capture structured bindings before C++20).
    const double d = queue.top().first;
    const int v = queue.top().second;
    queue.pop();
    if (d > dist[static_cast<std::size_t>(v)]) continue;
    settled += std::count(targets.begin(), targets.end(), v) > 0 ? 1 : 0;
    m.for_each_outgoing(v, [&](int h) {
      const int w = m.to_vertex(h);
      const double nd = d + (s.vertex(w) - s.vertex(v)).norm();
      if (nd < dist[static_cast<std::size_t>(w)]) dist[static_cast<std::size_t>(w)] = nd, queue.push({nd, w});
    });
  }
  double bound = std::numeric_limits<double>::infinity();
  for (int c : targets) bound = std::min(bound, dist[static_cast<std::size_t>(c)] + (s.vertex(c) - s.point(to)).norm());
  return bound;
}

// A copy of some faces of the level for CGAL, with the ids mapped both ways.
struct LegMesh {
  Mesh m;
  std::vector<int> vertex_of, face_of;  // level ids of the copy's vertices and faces
  std::vector<int> copy_of_face;        // the copy's face of a level face, −1 if left out
  int vertex(Mesh::Vertex_index v) const { return vertex_of[static_cast<std::size_t>(v)]; }
  int face(Mesh::Face_index f) const { return face_of[static_cast<std::size_t>(f)]; }
};

// The faces of `s` selected by `keep`; nullopt when they do not form a mesh CGAL accepts (a
// vertex whose kept faces are two separate fans).
std::optional<LegMesh> cgal_copy(const TriangleSurface& s, const std::function<bool(int)>& keep) {
  LegMesh out;
  out.copy_of_face.assign(static_cast<std::size_t>(s.n_faces()), -1);
  std::vector<int> copy_of_vertex(static_cast<std::size_t>(s.mesh().n_vertices()), -1);
  for (int f = 0; f < s.n_faces(); ++f) {
    if (!keep(f)) continue;
    std::array<Mesh::Vertex_index, 3> corners;
    for (int i = 0; i < 3; ++i) {
      const int v = s.corners(f)[i];
      int& c = copy_of_vertex[static_cast<std::size_t>(v)];
      if (c < 0) {
        const Vec3 p = s.vertex(v);
        c = static_cast<int>(out.m.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z())));
        out.vertex_of.push_back(v);
      }
      corners[static_cast<std::size_t>(i)] = Mesh::Vertex_index(static_cast<Mesh::size_type>(c));
    }
    const Mesh::Face_index added = out.m.add_face(corners[0], corners[1], corners[2]);
    if (added == Mesh::null_face()) return std::nullopt;
    out.copy_of_face[static_cast<std::size_t>(f)] = static_cast<int>(added);
    out.face_of.push_back(f);
  }
  return out;
}

// The part of the level a geodesic from `from` to `to` can pass through (or all of it).
LegMesh leg_mesh(const TriangleSurface& s, const SurfacePoint& from, const SurfacePoint& to) {
  const Vec3 a = s.point(from), b = s.point(to);
  // A face the path crosses holds a point of the ellipsoid; its corners lie within one edge.
  const double reach = edge_path_bound(s, from, to) + 2 * s.longest_edge();
  const auto inside = [&](int f) {
    for (int v : s.corners(f))
      if ((s.vertex(v) - a).norm() + (s.vertex(v) - b).norm() <= reach) return true;
    return false;
  };
  if (auto part = cgal_copy(s, inside)) return std::move(*part);
  if (auto all = cgal_copy(s, [](int) { return true; })) return std::move(*all);
  throw InvalidInput("geodesic paths: the level is not a manifold triangle mesh CGAL can copy");
}

// CGAL's barycentric coordinates of a face follow its halfedge cycle from halfedge(f).
ShortestPath::Face_location cgal_location(const LegMesh& leg, const TriangleSurface& s, const SurfacePoint& p) {
  const Mesh::Face_index f(static_cast<Mesh::size_type>(leg.copy_of_face[static_cast<std::size_t>(p.face)]));
  double w[3];
  Mesh::Halfedge_index h = leg.m.halfedge(f);
  for (int k = 0; k < 3; ++k, h = leg.m.next(h)) w[k] = p.bary[s.corner_of(p.face, leg.vertex(leg.m.source(h)))];
  return {f, ShortestPath::Barycentric_coordinates{{w[0], w[1], w[2]}}};
}

// One place the path passes: a vertex, a point of an edge, or a point inside a face (its ends).
struct PathStop {
  int vertex = -1;             // a vertex, or
  int edge_a = -1, edge_b = -1;  // the point (1 − t) a + t b of edge ab, or
  double t = 0;
  std::optional<SurfacePoint> inside;  // a point given in a face
};

// Records CGAL's walk back from the query to the source, in the level's ids.
struct StopRecorder {
  const LegMesh& leg;
  const TriangleSurface& s;
  std::vector<PathStop>& stops;
  void operator()(Mesh::Halfedge_index h, double t) {
    stops.push_back({-1, leg.vertex(leg.m.source(h)), leg.vertex(leg.m.target(h)), t, std::nullopt});
  }
  void operator()(Mesh::Vertex_index v) { stops.push_back({leg.vertex(v), -1, -1, 0, std::nullopt}); }
  void operator()(Mesh::Face_index f, const ShortestPath::Barycentric_coordinates& w) {
    SurfacePoint p{leg.face(f), Vec3::Zero()};
    Mesh::Halfedge_index h = leg.m.halfedge(f);
    for (int k = 0; k < 3; ++k, h = leg.m.next(h)) p.bary[s.corner_of(p.face, leg.vertex(leg.m.source(h)))] = w[k];
    stops.push_back({-1, -1, -1, 0, p});
  }
};

// The stop's weights in face f, when f holds it.
std::optional<Vec3> bary_in(const TriangleSurface& s, const PathStop& p, int f) {
  Vec3 b = Vec3::Zero();
  if (p.vertex >= 0) {
    const int c = s.corner_of(f, p.vertex);
    if (c < 0) return std::nullopt;
    b[c] = 1;
    return b;
  }
  if (p.edge_a >= 0) {
    const int ca = s.corner_of(f, p.edge_a), cb = s.corner_of(f, p.edge_b);
    if (ca < 0 || cb < 0) return std::nullopt;
    b[ca] = 1 - p.t;
    b[cb] = p.t;
    return b;
  }
  if (p.inside->face == f) return p.inside->bary;
  // A given point on an edge or at a corner of its face also belongs to the faces beyond.
  const Vec3 x = s.point(*p.inside), in_f = s.barycentric(f, x);
  const double off_plane = std::abs((x - s.vertex(s.corners(f)[0])).dot(s.face_normal(f)));
  if (in_f.minCoeff() < -1e-9 || off_plane > 1e-9 * (1 + s.longest_edge())) return std::nullopt;
  return in_f.cwiseMax(0.0) / in_f.cwiseMax(0.0).sum();
}

// Faces that may hold the stop (all faces around a vertex or an edge, the given face).
std::vector<int> faces_near(const TriangleSurface& s, const PathStop& p) {
  std::vector<int> out;
  const SurfaceMesh& m = s.mesh();
  const auto ring = [&](int v) {
    m.for_each_outgoing(v, [&](int h) {
      if (m.face(h) >= 0) out.push_back(m.face(h));
    });
  };
  if (p.vertex >= 0) ring(p.vertex);
  else if (p.edge_a >= 0) ring(p.edge_a);
  else {
    out.push_back(p.inside->face);
    for (int c : s.corners(p.inside->face)) ring(c);
  }
  return out;
}

Vec3 position(const TriangleSurface& s, const PathStop& p) {
  if (p.vertex >= 0) return s.vertex(p.vertex);
  if (p.edge_a >= 0) return (1 - p.t) * s.vertex(p.edge_a) + p.t * s.vertex(p.edge_b);
  return s.point(*p.inside);
}

// The path's end stop becomes the waypoint itself (as given), or the waypoint is added when
// CGAL's last stop is another place (it reports a source at a vertex as that vertex).
void pin_end(const TriangleSurface& s, std::vector<PathStop>& stops, bool at_front, const SurfacePoint& waypoint) {
  PathStop pinned;
  pinned.inside = waypoint;
  PathStop& end = at_front ? stops.front() : stops.back();
  if ((position(s, end) - s.point(waypoint)).norm() <= 1e-9 * (1 + s.longest_edge())) end = pinned;
  else if (at_front) stops.insert(stops.begin(), pinned);
  else stops.push_back(pinned);
}

SurfacePoint as_surface_point(const TriangleSurface& s, const PathStop& p) {
  if (p.inside) return *p.inside;
  const int f = faces_near(s, p).front();
  return {f, *bary_in(s, p, f)};
}

// Straight pieces between consecutive stops, each in a face holding both (CGAL's consecutive
// stops always share one); the straightest walk where they do not.
void append_pieces(const TriangleSurface& s, const PathStop& from, const PathStop& to, std::vector<FacePiece>& out) {
  for (int f : faces_near(s, from)) {
    const auto a = bary_in(s, from, f), b = bary_in(s, to, f);
    if (!a || !b) continue;
    if ((s.point({f, *a}) - s.point({f, *b})).norm() > 0) out.push_back({f, *a, *b});
    return;
  }
  for (const FacePiece& piece : walk_between(s, as_surface_point(s, from), as_surface_point(s, to)))
    if ((s.point({piece.face, piece.from}) - s.point({piece.face, piece.to})).norm() > 0) out.push_back(piece);
}

}  // namespace

std::vector<int> face_components(const TriangleSurface& s) {
  std::vector<int> parent(static_cast<std::size_t>(s.n_faces()));
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int f) {
    while (parent[static_cast<std::size_t>(f)] != f)
      f = parent[static_cast<std::size_t>(f)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(f)])];
    return f;
  };
  for (int f = 0; f < s.n_faces(); ++f)
    for (int i = 0; i < 3; ++i)
      if (const int g = s.across(f, i); g >= 0) parent[static_cast<std::size_t>(root(f))] = root(g);
  std::vector<int> id(static_cast<std::size_t>(s.n_faces()), -1), label(static_cast<std::size_t>(s.n_faces()), -1);
  int next = 0;
  for (int f = 0; f < s.n_faces(); ++f) {
    int& l = label[static_cast<std::size_t>(root(f))];
    if (l < 0) l = next++;
    id[static_cast<std::size_t>(f)] = l;
  }
  return id;
}

GeodesicPath geodesic_through(const TriangleSurface& s, const std::vector<SurfacePoint>& waypoints, bool closed) {
  const std::size_t n = waypoints.size();
  if (n < (closed ? 3u : 2u))
    throw InvalidInput(std::string("a ") + std::string(closed ? "closed " : "") + "geodesic path needs at least " +
                       (closed ? "3" : "2") + " waypoints, it has " + std::to_string(n));
  const std::vector<int> component = face_components(s);
  for (std::size_t i = 1; i < n; ++i)
    if (component[static_cast<std::size_t>(waypoints[i].face)] != component[static_cast<std::size_t>(waypoints[0].face)])
      throw InvalidInput(std::string("waypoint ") + std::to_string(i) + " lies on a different connected component of the surface "
                         "than waypoint 0: no path on the surface joins them");
  GeodesicPath out;
  out.line.closed = closed;
  double arc = 0;
  const std::size_t legs = closed ? n : n - 1;
  for (std::size_t leg = 0; leg < legs; ++leg) {
    const SurfacePoint& from = waypoints[leg];
    const SurfacePoint& to = waypoints[(leg + 1) % n];
    out.waypoint_arcs.push_back(arc);
    const LegMesh part = leg_mesh(s, from, to);
    ShortestPath paths(part.m);
    paths.add_source_point(cgal_location(part, s, from));
    std::vector<PathStop> stops;
    StopRecorder recorder{part, s, stops};
    const ShortestPath::Face_location target = cgal_location(part, s, to);
    const double distance = paths.shortest_path_sequence_to_source_points(target.first, target.second, recorder).first;
    if (distance < 0 || stops.empty())
      throw InvalidInput(std::string("no path on the surface joins waypoint ") + std::to_string(leg) + " to waypoint " +
                         std::to_string((leg + 1) % n));
    // CGAL reports from the query back to the source: turn it around and name the ends.
    std::reverse(stops.begin(), stops.end());
    pin_end(s, stops, true, from);
    pin_end(s, stops, false, to);
    const std::size_t before = out.line.pieces.size();
    for (std::size_t k = 1; k < stops.size(); ++k) append_pieces(s, stops[k - 1], stops[k], out.line.pieces);
    for (std::size_t k = before; k < out.line.pieces.size(); ++k) {
      const FacePiece& p = out.line.pieces[k];
      arc += (s.point({p.face, p.to}) - s.point({p.face, p.from})).norm();
    }
  }
  if (!closed) out.waypoint_arcs.push_back(arc);
  return out;
}

}  // namespace fairshape::feature
