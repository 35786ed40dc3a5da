#include "fairshape/subdivision/limit.h"

#include <Eigen/Geometry>
#include <cmath>

#include "fairshape/core/error.h"
#include "fairshape/subdivision/crease_rules.h"
#include "fairshape/subdivision/subdivider.h"

namespace fairshape {
namespace {

bool all_quads(const SurfaceMesh& m) {
  for (int f = 0; f < m.n_faces(); ++f)
    if (m.face_size(f) != 4) return false;
  return true;
}

// The vertex of quad face(h) diagonally opposite from_vertex(h).
int diagonal(const SurfaceMesh& m, int h) { return m.to_vertex(m.next(h)); }

void add_limit_row(const SurfaceMesh& m, int v, const SubdivisionOptions& opt, Triplets& t) {
  if (m.is_isolated(v)) { t.emplace_back(v, v, 1.0); return; }
  const auto hs = m.outgoing_halfedges(v);
  const int n = static_cast<int>(hs.size());
  // The rule at this level decides, as in OpenSubdiv (a semi-sharp crease that has not yet
  // decayed counts as sharp). Boundaries are creases, pinned one-face corners corners.
  const VertexRule rule = vertex_rule(m, v, opt.boundary);
  if (rule == VertexRule::Corner) { t.emplace_back(v, v, 1.0); return; }
  int a = -1, b = -1;
  if (rule == VertexRule::Crease && crease_neighbours(m, v, a, b)) {
    // Creases (boundary curves among them) are cubic B-splines: limit (a + 4v + b) / 6.
    t.emplace_back(v, v, 4.0 / 6.0);
    t.emplace_back(v, a, 1.0 / 6.0);
    t.emplace_back(v, b, 1.0 / 6.0);
    return;
  }
  if (opt.scheme == SchemeType::Loop) {  // (ω v + Σ p_i) / (ω + n), ω = 3 / (8 β)
    const double omega = 3.0 / (8.0 * loop_beta(n, opt.weights));
    t.emplace_back(v, v, omega / (omega + n));
    for (int h : hs) t.emplace_back(v, m.to_vertex(h), 1.0 / (omega + n));
    return;
  }
  // An interior vertex of valence 2 is where two quads fold onto each other: OpenSubdiv's
  // limit there is the vertex itself (its corner mask), and so is ours.
  if (n == 2) { t.emplace_back(v, v, 1.0); return; }
  // Catmull-Clark, all quads: (n² v + 4 Σ e_i + Σ d_i) / (n (n + 5)).
  const double den = n * (n + 5.0);
  t.emplace_back(v, v, n * n / den);
  for (int h : hs) {
    t.emplace_back(v, m.to_vertex(h), 4.0 / den);
    t.emplace_back(v, diagonal(m, h), 1.0 / den);
  }
}

// The fan of a boundary vertex from one boundary neighbour to the other: edge neighbours
// e_0 .. e_k (e_0 and e_k on the boundary) and, for quads, the diagonal d_i of the face
// between e_i and e_{i+1}.
struct BoundaryFan {
  std::vector<Vec3> e, d;
  int first_face = -1;
};

BoundaryFan boundary_fan(const SurfaceMesh& m, const std::vector<int>& hs) {
  BoundaryFan fan;  // hs[0] is the outgoing boundary half-edge; faces lie between hs[i], hs[i+1]
  for (std::size_t i = 1; i < hs.size(); ++i) {
    fan.e.push_back(m.position(m.to_vertex(hs[i])));
    fan.d.push_back(m.position(diagonal(m, hs[i])));
  }
  fan.e.push_back(m.position(m.to_vertex(hs[0])));
  fan.first_face = m.face(hs[1]);
  return fan;
}

// Tangent across the boundary, into the surface (up to sign), for the k = #faces fan.
Vec3 boundary_across(const BoundaryFan& fan, const Vec3& x, SchemeType scheme) {
  const auto& e = fan.e;
  const int k = static_cast<int>(e.size()) - 1;
  if (k == 1) return e[0] + e[1] - 2.0 * x;
  if (scheme == SchemeType::Loop) {
    if (k == 2) return e[1] - x;
    if (k == 3) return 2.0 * (e[1] + e[2]) - (e[0] + e[3]) - 2.0 * x;  // the regular case
    const double theta = M_PI / k;
    Vec3 t = std::sin(theta) * (e[0] + e[k]);
    for (int i = 1; i < k; ++i) t += 2.0 * (std::cos(theta) - 1.0) * std::sin(i * theta) * e[i];
    return t;
  }
  const auto& d = fan.d;  // Catmull-Clark, all quads
  if (k == 2) return 4.0 * (e[1] - x) - (e[0] + e[2]) + d[0] + d[1];
  const double theta = M_PI / k, c = std::cos(theta), s = std::sin(theta), R = (c + 1.0) / s;
  Vec3 t = 4.0 * R * (c - 1.0) * x - R * (1.0 + 2.0 * c) * (e[0] + e[k]);
  for (int i = 0; i < k; ++i) t += (std::sin(i * theta) + std::sin((i + 1) * theta)) * d[i];
  for (int i = 1; i < k; ++i) t += 4.0 * std::sin(i * theta) * e[i];
  return t;
}

// Newell normal of a face, to orient boundary normals like the surface.
Vec3 face_normal(const SurfaceMesh& m, int f) {
  Vec3 n = Vec3::Zero();
  const auto vs = m.face_vertices(f);
  for (std::size_t i = 0; i < vs.size(); ++i) n += m.position(vs[i]).cross(m.position(vs[(i + 1) % vs.size()]));
  return n;
}

// One side of an interior crease: the faces from outgoing half-edge hs[i] counter-clockwise
// to hs[j] (indices mod n), laid out like a boundary fan (e from to(hs[i]) to to(hs[j])).
BoundaryFan sector_fan(const SurfaceMesh& m, const std::vector<int>& hs, int i, int j) {
  const int n = static_cast<int>(hs.size());
  BoundaryFan fan;
  for (int k = i;; k = (k + 1) % n) {
    fan.e.push_back(m.position(m.to_vertex(hs[k])));
    if (k == j) break;
    fan.d.push_back(m.position(diagonal(m, hs[k])));
  }
  fan.first_face = m.face(hs[i]);
  return fan;
}

// The unit normal of one crease side: the crease's own tangent (its cubic B-spline's) and
// the across-tangent of the side, which is then the boundary of a surface of its own.
Vec3 sector_normal(const SurfaceMesh& m, const BoundaryFan& fan, const Vec3& x, SchemeType scheme) {
  const Vec3 along = 0.5 * (fan.e.back() - fan.e.front());
  Vec3 n = along.cross(boundary_across(fan, x, scheme));
  if (n.dot(face_normal(m, fan.first_face)) < 0) n = -n;
  return n.normalized();
}

// Tangents at an interior vertex on a sharp crease. The limit surface has a normal on each
// side; the frame takes their bisector (normal to the crease tangent, which both sides
// share) so that details are measured symmetrically across the crease. t1 runs along the
// crease, t2 = n × t1, so t1 × t2 points along the bisector.
void crease_tangents(const SurfaceMesh& m, int v, const std::vector<int>& hs, SchemeType scheme, Vec3& t1, Vec3& t2) {
  const int n = static_cast<int>(hs.size());
  int i = -1, j = -1;
  for (int k = 0; k < n; ++k)
    if (effective_edge_sharpness(m, SurfaceMesh::edge(hs[k])) > 0.0f) (i < 0 ? i : j) = k;
  const Vec3 x = m.position(v);
  const Vec3 n1 = sector_normal(m, sector_fan(m, hs, i, j), x, scheme);
  Vec3 normal = n1 + sector_normal(m, sector_fan(m, hs, j, i), x, scheme);
  // Sides folded flat onto each other (opposite normals) have no bisector: take the first.
  normal = normal.norm() > 1e-8 ? Vec3(normal.normalized()) : n1;
  t1 = 0.5 * (m.position(m.to_vertex(hs[j])) - m.position(m.to_vertex(hs[i])));
  t2 = normal.cross(t1);
}

// At a corner the limit surface has no tangent plane: the frame uses the incident faces'
// normals weighted by their angles at v (documented approximation; angle weights make it
// independent of how a flat side is split into faces), t1 towards the first edge neighbour.
void corner_tangents(const SurfaceMesh& m, int v, const std::vector<int>& hs, Vec3& t1, Vec3& t2) {
  Vec3 normal = Vec3::Zero();
  const Vec3 x = m.position(v);
  for (int h : hs) {
    if (m.is_boundary_halfedge(h)) continue;
    const Vec3 a = m.position(m.to_vertex(h)) - x, b = m.position(m.from_vertex(m.prev(h))) - x;
    const double angle = std::atan2(a.cross(b).norm(), a.dot(b));
    normal += angle * face_normal(m, m.face(h)).normalized();
  }
  normal.normalize();
  const Vec3 e = m.position(m.to_vertex(hs.front())) - m.position(v);
  t1 = e - e.dot(normal) * normal;
  t2 = normal.cross(t1);
}

}  // namespace

bool vertex_limit_mask_exact(const SurfaceMesh& m, int v) {
  const float vertex = m.vertex_sharpness(v);
  if (vertex >= kInfiniteSharpness) return true;
  if (vertex > 0.0f) return false;
  int infinite = 0, semi = 0;
  m.for_each_outgoing(v, [&](int h) {
    const float s = effective_edge_sharpness(m, SurfaceMesh::edge(h));
    infinite += s >= kInfiniteSharpness;
    semi += s > 0.0f && s < kInfiniteSharpness;
  });
  return semi == 0 && infinite != 1;
}

SparseMatrix limit_matrix(const SurfaceMesh& mesh, const SubdivisionOptions& opt) {
  if (opt.scheme == SchemeType::CatmullClark && !all_quads(mesh)) {
    SparseMatrix S;
    const SurfaceMesh fine = subdivide_once(mesh, opt, kFastestBackend, &S);
    const SparseMatrix L = limit_matrix(fine, opt);
    return SparseMatrix(L.topRows(mesh.n_vertices())) * S;  // vertex children keep their ids
  }
  if (opt.scheme == SchemeType::Loop) require_triangles(mesh, "limit");
  Triplets t;
  for (int v = 0; v < mesh.n_vertices(); ++v) add_limit_row(mesh, v, opt, t);
  SparseMatrix L(mesh.n_vertices(), mesh.n_vertices());
  L.setFromTriplets(t.begin(), t.end());
  return L;
}

MatrixX3 limit_positions(const SurfaceMesh& mesh, const SubdivisionOptions& opt) {
  return limit_matrix(mesh, opt) * mesh.positions();
}

namespace {

// The two limit tangents of one vertex (zero for an isolated one): limit_tangents' per-vertex
// rule, shared with limit_normal_at so that both give the same numbers.
void vertex_limit_tangents(const SurfaceMesh& mesh, const SubdivisionOptions& opt, int v, Vec3& a, Vec3& b) {
  a = Vec3::Zero(), b = Vec3::Zero();
  if (mesh.is_isolated(v)) return;
  const auto hs = mesh.outgoing_halfedges(v);
  const int n = static_cast<int>(hs.size());
  if (mesh.has_sharpness()) {  // tagged creases and corners (boundaries keep their own frame below)
    const VertexRule rule = vertex_rule(mesh, v, opt.boundary);
    const bool pinned = mesh.is_boundary_vertex(v) && n == 2 && opt.boundary == BoundaryMode::EdgeAndCorner;
    const bool own_frame = rule == VertexRule::Corner ? !pinned
                                                      : rule == VertexRule::Crease && !mesh.is_boundary_vertex(v);
    if (own_frame) {
      if (rule == VertexRule::Corner) corner_tangents(mesh, v, hs, a, b);
      else crease_tangents(mesh, v, hs, opt.scheme, a, b);
      return;
    }
  }
  if (mesh.is_boundary_vertex(v)) {
    // Along the boundary curve (the cubic B-spline's derivative), then across it, with the
    // pair ordered so that t1 × t2 points to the side the faces face.
    const BoundaryFan fan = boundary_fan(mesh, hs);
    a = 0.5 * (fan.e.back() - fan.e.front());
    b = boundary_across(fan, mesh.position(v), opt.scheme);
    if (a.cross(b).dot(face_normal(mesh, fan.first_face)) < 0) b = -b;
    return;
  }
  if (n == 2 && opt.scheme == SchemeType::CatmullClark) {  // the corner frame, as the limit above
    a = mesh.position(mesh.to_vertex(hs[0])) - mesh.position(v);
    b = mesh.position(mesh.to_vertex(hs[1])) - mesh.position(v);
    if (a.cross(b).dot(face_normal(mesh, mesh.face(hs[0]))) < 0) std::swap(a, b);
    return;
  }
  for (int i = 0; i < n; ++i) {
    const double c0 = std::cos(2 * M_PI * i / n), s0 = std::sin(2 * M_PI * i / n);
    const Vec3 e = mesh.position(mesh.to_vertex(hs[i]));
    if (opt.scheme == SchemeType::Loop) {
      a += c0 * e;
      b += s0 * e;
      continue;
    }
    // Catmull-Clark eigenvector masks (Halstead, Kass, DeRose 1993).
    const double An = 1 + std::cos(2 * M_PI / n) + std::cos(M_PI / n) * std::sqrt(2 * (9 + std::cos(2 * M_PI / n)));
    const double c1 = std::cos(2 * M_PI * (i + 1) / n), s1 = std::sin(2 * M_PI * (i + 1) / n);
    const Vec3 d = mesh.position(diagonal(mesh, hs[i]));
    a += An * c0 * e + (c0 + c1) * d;
    b += An * s0 * e + (s0 + s1) * d;
  }
}

Vec3 unit_cross(const Vec3& a, const Vec3& b) {
  const Vec3 c = a.cross(b);
  const double len = c.norm();
  return len > 0 ? Vec3(c / len) : Vec3::Zero();
}

}  // namespace

void limit_tangents(const SurfaceMesh& mesh, const SubdivisionOptions& opt, MatrixX3& t1, MatrixX3& t2) {
  if (opt.scheme == SchemeType::CatmullClark && !all_quads(mesh)) {
    const SurfaceMesh fine = subdivide_once(mesh, opt, kFastestBackend);
    MatrixX3 f1, f2;
    limit_tangents(fine, opt, f1, f2);
    t1 = f1.topRows(mesh.n_vertices());
    t2 = f2.topRows(mesh.n_vertices());
    return;
  }
  t1.setZero(mesh.n_vertices(), 3);
  t2.setZero(mesh.n_vertices(), 3);
  for (int v = 0; v < mesh.n_vertices(); ++v) {
    Vec3 a, b;
    vertex_limit_tangents(mesh, opt, v, a, b);
    t1.row(v) = a.transpose();
    t2.row(v) = b.transpose();
  }
}

Vec3 limit_normal_at(const SurfaceMesh& mesh, const SubdivisionOptions& opt, int v) {
  if (opt.scheme == SchemeType::CatmullClark && !all_quads(mesh))
    throw InvalidInput("limit_normal_at: a Catmull-Clark mesh with non-quad faces (refine it once first)");
  Vec3 a, b;
  vertex_limit_tangents(mesh, opt, v, a, b);
  return unit_cross(a, b);
}

MatrixX3 limit_normals(const SurfaceMesh& mesh, const SubdivisionOptions& opt) {
  MatrixX3 t1, t2, n(mesh.n_vertices(), 3);
  limit_tangents(mesh, opt, t1, t2);
  for (int v = 0; v < mesh.n_vertices(); ++v) n.row(v) = unit_cross(Vec3(t1.row(v)), Vec3(t2.row(v))).transpose();
  return n;
}

}  // namespace fairshape
