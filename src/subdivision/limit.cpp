#include "subdivision/limit.h"

#include <Eigen/Geometry>
#include <cmath>

#include "subdivision/subdivider.h"

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
  if (m.is_boundary_vertex(v)) {
    if (n == 2 && opt.boundary == BoundaryMode::EdgeAndCorner) { t.emplace_back(v, v, 1.0); return; }
    // Boundary curves are cubic B-splines: limit (a + 4v + b) / 6.
    t.emplace_back(v, v, 4.0 / 6.0);
    t.emplace_back(v, m.to_vertex(hs.front()), 1.0 / 6.0);
    t.emplace_back(v, m.from_vertex(m.prev(hs.front())), 1.0 / 6.0);
    return;
  }
  if (opt.scheme == SchemeType::Loop) {  // (ω v + Σ p_i) / (ω + n), ω = 3 / (8 β)
    const double omega = 3.0 / (8.0 * loop_beta(n, opt.weights));
    t.emplace_back(v, v, omega / (omega + n));
    for (int h : hs) t.emplace_back(v, m.to_vertex(h), 1.0 / (omega + n));
    return;
  }
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

}  // namespace

SparseMatrix limit_matrix(const SurfaceMesh& mesh, const SubdivisionOptions& opt) {
  if (opt.scheme == SchemeType::CatmullClark && !all_quads(mesh)) {
    SparseMatrix S;
    const SurfaceMesh fine = subdivide_once(mesh, opt, Backend::Optimized, &S);
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

void limit_tangents(const SurfaceMesh& mesh, const SubdivisionOptions& opt, MatrixX3& t1, MatrixX3& t2) {
  if (opt.scheme == SchemeType::CatmullClark && !all_quads(mesh)) {
    const SurfaceMesh fine = subdivide_once(mesh, opt, Backend::Optimized);
    MatrixX3 f1, f2;
    limit_tangents(fine, opt, f1, f2);
    t1 = f1.topRows(mesh.n_vertices());
    t2 = f2.topRows(mesh.n_vertices());
    return;
  }
  t1.setZero(mesh.n_vertices(), 3);
  t2.setZero(mesh.n_vertices(), 3);
  for (int v = 0; v < mesh.n_vertices(); ++v) {
    if (mesh.is_isolated(v)) continue;
    const auto hs = mesh.outgoing_halfedges(v);
    const int n = static_cast<int>(hs.size());
    Vec3 a = Vec3::Zero(), b = Vec3::Zero();
    if (mesh.is_boundary_vertex(v)) {
      // Along the boundary curve (the cubic B-spline's derivative), then across it, with the
      // pair ordered so that t1 × t2 points to the side the faces face.
      const BoundaryFan fan = boundary_fan(mesh, hs);
      a = 0.5 * (fan.e.back() - fan.e.front());
      b = boundary_across(fan, mesh.position(v), opt.scheme);
      if (a.cross(b).dot(face_normal(mesh, fan.first_face)) < 0) b = -b;
      t1.row(v) = a.transpose();
      t2.row(v) = b.transpose();
      continue;
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
    t1.row(v) = a.transpose();
    t2.row(v) = b.transpose();
  }
}

MatrixX3 limit_normals(const SurfaceMesh& mesh, const SubdivisionOptions& opt) {
  MatrixX3 t1, t2, n(mesh.n_vertices(), 3);
  limit_tangents(mesh, opt, t1, t2);
  for (int v = 0; v < mesh.n_vertices(); ++v) {
    const Vec3 c = Vec3(t1.row(v)).cross(Vec3(t2.row(v)));
    const double len = c.norm();
    n.row(v) = (len > 0 ? Vec3(c / len) : Vec3::Zero()).transpose();
  }
  return n;
}

}  // namespace fairshape
