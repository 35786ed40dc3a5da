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
  face_longest_.assign(static_cast<std::size_t>(nf), 0.0);
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
    for (int i = 0; i < 3; ++i) face_longest_[f] = std::max(face_longest_[f], (vertex(c[(i + 1) % 3]) - vertex(c[i])).norm());
    longest_edge_ = std::max(longest_edge_, face_longest_[f]);
    const Vec3 n = (vertex(c[1]) - vertex(c[0])).cross(vertex(c[2]) - vertex(c[0]));
    face_normals_.row(f) = (n.norm() > 0 ? n.normalized() : Vec3::Zero()).transpose();
  }
}

void TriangleSurface::refresh(const std::vector<int>& moved) {
  const SurfaceMesh& m = *mesh_;
  std::vector<int> faces, ring;
  std::vector<char> seen_face(static_cast<std::size_t>(m.n_faces()), 0), seen_vertex(static_cast<std::size_t>(m.n_vertices()), 0);
  for (int v : moved) {
    if (!seen_vertex[static_cast<std::size_t>(v)]) seen_vertex[static_cast<std::size_t>(v)] = 1, ring.push_back(v);
    m.for_each_outgoing(v, [&](int h) {
      const int w = m.to_vertex(h), f = m.face(h);
      if (!seen_vertex[static_cast<std::size_t>(w)]) seen_vertex[static_cast<std::size_t>(w)] = 1, ring.push_back(w);
      if (f >= 0 && !seen_face[static_cast<std::size_t>(f)]) seen_face[static_cast<std::size_t>(f)] = 1, faces.push_back(f);
    });
  }
  SubdivisionOptions loop;
  loop.scheme = SchemeType::Loop;
  for (int v : ring) normals_.row(v) = limit_normal_at(m, loop, v).transpose();
  bool may_shrink = false;
  for (int f : faces) {
    const auto& c = corners_[f];
    const Vec3 n = (vertex(c[1]) - vertex(c[0])).cross(vertex(c[2]) - vertex(c[0]));
    face_normals_.row(f) = (n.norm() > 0 ? n.normalized() : Vec3::Zero()).transpose();
    double longest = 0;
    for (int i = 0; i < 3; ++i) longest = std::max(longest, (vertex(c[(i + 1) % 3]) - vertex(c[i])).norm());
    // The face that held the longest edge got shorter: only a scan knows the new longest.
    may_shrink = may_shrink || (face_longest_[f] == longest_edge_ && longest < longest_edge_);
    face_longest_[f] = longest;
  }
  if (may_shrink) longest_edge_ = *std::max_element(face_longest_.begin(), face_longest_.end());
  else
    for (int f : faces) longest_edge_ = std::max(longest_edge_, face_longest_[f]);
  locator_.reset();
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
