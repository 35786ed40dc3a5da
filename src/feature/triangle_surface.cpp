#include "feature/triangle_surface.h"

#include <algorithm>

#include "core/error.h"
#include "remesh/closest_point.h"
#include "subdivision/limit.h"

namespace fairshape::feature {

TriangleSurface::TriangleSurface(const SurfaceMesh& mesh, MatrixX3 vertex_normals)
    : mesh_(&mesh), normals_(std::move(vertex_normals)) {
  if (normals_.rows() != mesh.n_vertices())
    throw InvalidInput("feature surface: " + std::to_string(normals_.rows()) + " normals for " +
                       std::to_string(mesh.n_vertices()) + " vertices");
  const int nf = mesh.n_faces();
  corners_.resize(nf);
  across_.resize(nf);
  face_normals_.resize(nf, 3);
  for (int f = 0; f < nf; ++f) {
    if (mesh.face_size(f) != 3)
      throw InvalidInput("feature curves need a triangle (Loop) level, but face " + std::to_string(f) + " has " +
                         std::to_string(mesh.face_size(f)) + " corners");
    int h = mesh.face_halfedge(f);
    for (int i = 0; i < 3; ++i, h = mesh.next(h)) {
      corners_[f][i] = mesh.from_vertex(h);
      across_[f][i] = mesh.face(mesh.twin(h));
    }
    const auto& c = corners_[f];
    for (int i = 0; i < 3; ++i) longest_edge_ = std::max(longest_edge_, (vertex(c[(i + 1) % 3]) - vertex(c[i])).norm());
    const Vec3 n = (vertex(c[1]) - vertex(c[0])).cross(vertex(c[2]) - vertex(c[0]));
    face_normals_.row(f) = (n.norm() > 0 ? n.normalized() : Vec3::Zero()).transpose();
  }
}

Vec3 TriangleSurface::point(const SurfacePoint& p) const {
  const auto& c = corners_[p.face];
  return p.bary[0] * vertex(c[0]) + p.bary[1] * vertex(c[1]) + p.bary[2] * vertex(c[2]);
}

Vec3 TriangleSurface::normal(const SurfacePoint& p) const {
  const auto& c = corners_[p.face];
  const Vec3 n = p.bary[0] * vertex_normal(c[0]) + p.bary[1] * vertex_normal(c[1]) + p.bary[2] * vertex_normal(c[2]);
  const double len = n.norm();
  return len > 1e-300 ? Vec3(n / len) : face_normal(p.face);
}

Vec3 TriangleSurface::barycentric_rate(int f, const Vec3& d) const {
  // d = a e1 + b e2 with e1 = p1 − p0, e2 = p2 − p0 (least squares: d lies in the plane).
  const auto& c = corners_[f];
  const Vec3 e1 = vertex(c[1]) - vertex(c[0]), e2 = vertex(c[2]) - vertex(c[0]);
  const double g11 = e1.dot(e1), g12 = e1.dot(e2), g22 = e2.dot(e2);
  const double det = g11 * g22 - g12 * g12;
  const double r1 = e1.dot(d), r2 = e2.dot(d);
  const double a = (g22 * r1 - g12 * r2) / det, b = (g11 * r2 - g12 * r1) / det;
  return {-a - b, a, b};
}

Vec3 TriangleSurface::barycentric(int f, const Vec3& x) const {
  const Vec3 rate = barycentric_rate(f, x - vertex(corners_[f][0]));
  return Vec3(1.0, 0.0, 0.0) + rate;
}

int TriangleSurface::corner_of(int f, int v) const {
  for (int i = 0; i < 3; ++i)
    if (corners_[f][i] == v) return i;
  return -1;
}

const ClosestPointQuery& TriangleSurface::locator() const {
  if (!locator_) locator_ = std::make_shared<const ClosestPointQuery>(*mesh_);
  return *locator_;
}

MatrixX3 loop_limit_normals(const SurfaceMesh& mesh) {
  SubdivisionOptions opt;
  opt.scheme = SchemeType::Loop;
  return limit_normals(mesh, opt);
}

}  // namespace fairshape::feature
