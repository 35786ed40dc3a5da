#include "fairshape/feature/ray_unrolling.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fairshape::feature {
namespace {

// A crossing this close (in barycentric terms) to an edge's end point passes the vertex.
constexpr double kVertexSnap = 1e-9;
constexpr int kMaxSteps = 1 << 20;

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

Vec3 project_onto_plane(const Vec3& d, const Vec3& n) { return d - d.dot(n) * n; }

// Barycentric coordinates of corner k (weight 1 there, 0 at the other two).
Vec3 at_corner(int k) { return Vec3::Unit(k); }

// The face of v's one-ring the tangent-plane direction d enters, with the ring projected to the
// tangent plane (one-to-one or FlatnessError). `sector` = −1 when d leaves the surface there.
struct RingSector {
  int face = -1;
  int corner_v = -1;  // v's corner in that face
  Eigen::Vector2d a2, b2, d2;
  Vec3 u, w;  // the tangent plane's axes
};

RingSector find_sector(const TriangleSurface& s, int v, const Vec3& d) {
  RingSector out;
  const Vec3 n = s.vertex_normal(v);
  out.u = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
  out.w = n.cross(out.u);
  const Vec3 p = s.vertex(v);
  const auto to2 = [&](const Vec3& x) { return Eigen::Vector2d((x - p).dot(out.u), (x - p).dot(out.w)); };
  out.d2 = Eigen::Vector2d(d.dot(out.u), d.dot(out.w)).normalized();
  int containing = 0;  // sectors strictly around d: more than one when the ring wraps twice
  s.mesh().for_each_outgoing(v, [&](int h) {
    const int f = s.mesh().face(h);
    if (f < 0) return;
    const int i = s.corner_of(f, v);
    const Eigen::Vector2d a2 = to2(s.vertex(s.corners(f)[(i + 1) % 3])), b2 = to2(s.vertex(s.corners(f)[(i + 2) % 3]));
    if (!(cross2(a2, b2) > 0))
      throw FlatnessError(v, "vertex " + std::to_string(v) + ": its one-ring folds over when projected to the tangent "
                                 "plane (the surface is not flat at this scale; draw the feature on a finer level or "
                                 "use a smaller radius)");
    if (cross2(a2, out.d2) > 0 && cross2(out.d2, b2) > 0) ++containing;
    if (out.face < 0 && cross2(a2, out.d2) >= 0 && cross2(out.d2, b2) >= 0) {
      out.face = f;
      out.corner_v = i;
      out.a2 = a2;
      out.b2 = b2;
    }
  });
  if (containing > 1)
    throw FlatnessError(v, "vertex " + std::to_string(v) + ": its one-ring wraps more than once around its tangent "
                               "plane (the surface is not flat at this scale; draw the feature on a finer level or "
                               "use a smaller radius)");
  return out;
}

// The walk's state: a point of face f (barycentric b) moving in the in-plane direction d.
struct Walker {
  Walker(const TriangleSurface& surface, int face, const Vec3& bary, const Vec3& dir)
      : s(surface), f(face), b(bary), d(dir) {}
  const TriangleSurface& s;
  int f;
  Vec3 b, d;

  Vec3 position() const { return s.point({f, b}); }

  // d/dt of the barycentric coordinates, kept until f or d change (a step uses it twice).
  const Vec3& rate() const {
    if (f != rate_f_ || d != rate_d_) {
      rate_ = s.barycentric_rate(f, d);
      rate_f_ = f;
      rate_d_ = d;
    }
    return rate_;
  }
  // Distance to the face's boundary along d, and the corner whose weight reaches zero there.
  double exit_distance(int& vanishing) const {
    const Vec3& r = rate();
    double t = std::numeric_limits<double>::infinity();
    vanishing = -1;
    for (int i = 0; i < 3; ++i)
      if (r[i] < 0) {
        const double ti = std::max(b[i], 0.0) / -r[i];
        if (ti < t) t = ti, vanishing = i;
      }
    return t;
  }
  void advance(double t) {
    b += t * rate();
    for (int i = 0; i < 3; ++i) b[i] = std::max(b[i], 0.0);
    b /= b.sum();
  }
  // At a point of edge e of f: the vertex it sits on (or −1).
  int snapped_vertex(int e) const {
    const int i = e, j = (e + 1) % 3;
    if (b[i] < kVertexSnap) return s.corners(f)[j];
    if (b[j] < kVertexSnap) return s.corners(f)[i];
    return -1;
  }
  // Crosses edge e (the point is on it) with the double projection. False at the boundary.
  // When the projected direction does not enter the next face (a ray grazing the edge), the
  // walk goes on along the edge towards the end point d points to: *along_edge is that vertex.
  bool cross_edge(int e, int* along_edge) {
    *along_edge = -1;
    const int g = s.across(f, e);
    if (g < 0) return false;
    const int va = s.corners(f)[e], vb = s.corners(f)[(e + 1) % 3];
    const Vec3 ne = (b[e] * s.vertex_normal(va) + b[(e + 1) % 3] * s.vertex_normal(vb)).normalized();
    Vec3 dg = project_onto_plane(project_onto_plane(d, ne), s.face_normal(g));
    Vec3 bg = Vec3::Zero();
    bg[s.corner_of(g, va)] = b[e];
    bg[s.corner_of(g, vb)] = b[(e + 1) % 3];
    const int opposite = 3 - s.corner_of(g, va) - s.corner_of(g, vb);
    const double len = dg.norm();
    if (len < 1e-14) {
      *along_edge = (s.vertex(vb) - s.vertex(va)).dot(d) > 0 ? vb : va;
      return true;
    }
    dg /= len;
    const Vec3 rate_g = s.barycentric_rate(g, dg);
    if (rate_g[opposite] <= 0) {
      *along_edge = (s.vertex(vb) - s.vertex(va)).dot(d) > 0 ? vb : va;
      return true;
    }
    f = g;
    b = bg;
    d = dg;
    rate_f_ = g, rate_d_ = dg, rate_ = rate_g;
    return true;
  }

 private:
  mutable int rate_f_ = -1;
  mutable Vec3 rate_d_ = Vec3::Zero(), rate_ = Vec3::Zero();
};

}  // namespace

UnrolledRay unroll_ray(const TriangleSurface& s, const SurfacePoint& start, const Vec3& direction, double length) {
  UnrolledRay ray;
  ray.path.reserve(32);
  ray.arc.reserve(32);
  Walker w(s, start.face, start.bary, project_onto_plane(direction, s.face_normal(start.face)));
  if (w.d.norm() < 1e-300) throw InvalidInput("unroll_ray: the direction is normal to the face");
  w.d.normalize();
  double done = 0;
  ray.path.push_back(w.position());
  ray.arc.push_back(0);
  const auto record = [&](double step) {
    done += step;
    ray.path.push_back(w.position());
    ray.arc.push_back(done);
  };
  int vertex = -1;  // ≥ 0: the walk stands on this vertex
  // At a point of edge e of the current face: stand on its vertex, or cross the edge; a ray
  // grazing the edge runs along it to its end point. False when the ray ends here.
  const auto leave_by_edge = [&](int e) {
    vertex = w.snapped_vertex(e);
    if (vertex >= 0) return true;
    int along = -1;
    if (!w.cross_edge(e, &along)) {
      ray.hit_boundary = true;
      return false;
    }
    if (along < 0) return true;
    const double to_vertex = (s.vertex(along) - w.position()).norm();
    if (length - done <= to_vertex) {
      const Vec3 x = w.position() + (length - done) * (s.vertex(along) - w.position()).normalized();
      w.b = s.barycentric(w.f, x);
      record(length - done);
      return false;
    }
    w.b = at_corner(s.corner_of(w.f, along));
    record(to_vertex);
    vertex = along;
    return true;
  };
  for (int step = 0; step < kMaxSteps; ++step) {
    const double remaining = length - done;
    if (vertex >= 0) {
      const RingSector ring = find_sector(s, vertex, w.d);
      if (ring.face < 0) {
        ray.hit_boundary = true;
        break;
      }
      // The ray from the vertex along d2 meets the ring's edge a2 + λ (b2 − a2) at distance t.
      const Eigen::Vector2d e2 = ring.b2 - ring.a2;
      const double den = cross2(ring.d2, e2);
      const double t = cross2(ring.a2, e2) / den, lambda = std::clamp(cross2(ring.a2, ring.d2) / den, 0.0, 1.0);
      const Vec3 d3 = ring.d2.x() * ring.u + ring.d2.y() * ring.w;
      const int cv = ring.corner_v, ca = (cv + 1) % 3, cb = (cv + 2) % 3;
      w.f = ring.face;
      w.d = project_onto_plane(d3, s.face_normal(w.f)).normalized();
      if (remaining <= t) {  // ends inside the sector: its point in the projected triangle (0, a2, b2)
        const Eigen::Vector2d q = remaining * ring.d2;
        const double area = cross2(ring.a2, ring.b2);
        w.b = Vec3::Zero();
        w.b[ca] = cross2(q, ring.b2) / area;
        w.b[cb] = cross2(ring.a2, q) / area;
        w.b[cv] = 1 - w.b[ca] - w.b[cb];
        record(remaining);
        break;
      }
      w.b = Vec3::Zero();
      w.b[ca] = 1 - lambda;
      w.b[cb] = lambda;
      w.d = d3;  // still in the vertex's tangent plane: the edge crossing projects it twice
      record(t);
      if (!leave_by_edge(ca)) break;
      continue;
    }
    int vanishing = -1;
    const double t = w.exit_distance(vanishing);
    if (remaining <= t || vanishing < 0) {
      w.advance(remaining);
      record(remaining);
      break;
    }
    w.advance(t);
    w.b[vanishing] = 0;
    record(t);
    if (!leave_by_edge((vanishing + 1) % 3)) break;  // the edge opposite the vanishing corner
  }
  if (vertex >= 0 && ray.hit_boundary) {  // stopped on a boundary vertex
    w.b = at_corner(s.corner_of(w.f, vertex));
  }
  ray.end = {w.f, w.b};
  ray.end_direction = w.d.normalized();
  return ray;
}

std::vector<FacePiece> walk_between(const TriangleSurface& s, const SurfacePoint& from, const SurfacePoint& to) {
  std::vector<FacePiece> pieces;
  const Vec3 target = s.point(to);
  Walker w(s, from.face, from.bary, Vec3::Zero());
  const double scale = (s.point(from) - target).norm() + 1e-300;
  const auto arrived_in = [&](int f, Vec3& bary) {
    if (f == to.face) {
      bary = to.bary;
      return true;
    }
    const Vec3 b = s.barycentric(f, target);
    const double off_plane = std::abs((target - s.vertex(s.corners(f)[0])).dot(s.face_normal(f)));
    if (b.minCoeff() < -1e-9 || off_plane > 1e-9 * scale) return false;
    bary = b;
    return true;
  };
  const auto where = [&] {
    const Vec3 p = s.point(from);
    return "from (" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ", " + std::to_string(p.z()) + ")";
  };
  // Goes to vertex v of the current face and on into the ring face that faces the target.
  std::vector<int> passed;  // few: a walk passes a handful of vertices
  const auto through_vertex = [&](int v) {
    if (std::find(passed.begin(), passed.end(), v) != passed.end())
      throw InvalidInput("the curve cannot be followed on the surface " + where() + ": the walk towards the next point "
                         "circles around vertex " + std::to_string(v) + " (the surface is not flat at this scale)");
    passed.push_back(v);
    const RingSector ring = find_sector(s, v, project_onto_plane(target - s.vertex(v), s.vertex_normal(v)));
    if (ring.face < 0) throw InvalidInput("the curve leaves the surface at boundary vertex " + std::to_string(v));
    w.f = ring.face;
    w.b = at_corner(ring.corner_v);
  };
  int entered_by = -1;  // the mesh edge the walk came in through
  const int max_steps = 4 * s.n_faces() + 16;
  for (int step = 0; step < max_steps; ++step) {
    Vec3 end_bary;
    if (arrived_in(w.f, end_bary)) {
      pieces.push_back({w.f, w.b, end_bary});
      return pieces;
    }
    w.d = project_onto_plane(target - w.position(), s.face_normal(w.f));
    int vanishing = -1;
    double t = 0;
    if (w.d.norm() > 1e-14 * scale) {
      w.d.normalize();
      t = w.exit_distance(vanishing);
    }
    if (vanishing < 0)
      throw InvalidInput("the curve leaves the surface " + where() + ": the walk stalls in face " + std::to_string(w.f));
    const int e = (vanishing + 1) % 3;
    int h = s.mesh().face_halfedge(w.f);
    for (int i = 0; i < e; ++i) h = s.mesh().next(h);
    if (SurfaceMesh::edge(h) == entered_by) {
      // The target lies behind the edge seen from both of its faces: follow the edge to the end
      // point nearer the target, then pass that vertex.
      const int va = s.corners(w.f)[e], vb = s.corners(w.f)[(e + 1) % 3];
      const int v = (s.vertex(va) - target).norm() < (s.vertex(vb) - target).norm() ? va : vb;
      pieces.push_back({w.f, w.b, at_corner(s.corner_of(w.f, v))});
      through_vertex(v);
      entered_by = -1;
      continue;
    }
    const Vec3 start_bary = w.b;
    w.advance(t);
    w.b[vanishing] = 0;
    pieces.push_back({w.f, start_bary, w.b});
    if (const int v = w.snapped_vertex(e); v >= 0) {
      through_vertex(v);
      entered_by = -1;
      continue;
    }
    int along = -1;
    if (!w.cross_edge(e, &along))
      throw InvalidInput("the curve leaves the surface across a boundary edge of face " + std::to_string(w.f));
    entered_by = SurfaceMesh::edge(h);
    if (along >= 0) {  // grazing the edge: along it to its end point (still in this face)
      const Vec3 end = at_corner(s.corner_of(w.f, along));
      pieces.push_back({w.f, w.b, end});
      w.b = end;
      entered_by = -1;
    }
  }
  throw InvalidInput("the curve cannot be followed on the surface " + where() + ": the walk towards the next point "
                     "did not arrive");
}

}  // namespace fairshape::feature
