#include "fairshape/feature/triangle_surface.h"

#include <algorithm>

#include "fairshape/core/error.h"
#include "fairshape/remesh/closest_point.h"
#include "fairshape/subdivision/limit.h"

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
