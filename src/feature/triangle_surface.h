// A triangle mesh of one hierarchy level seen as a piecewise flat surface with a smooth normal
// field: points given by (face, barycentric coordinates), normals interpolated linearly from the
// limit normals of the corners (Khodakovsky & Schröder, "Fine level feature editing for
// subdivision surfaces", §2.1.2: "for an edge point we use linear interpolation between the two
// edge endpoint normals"). Corner i of a face runs along edge i to corner i + 1.
#pragma once

#include <array>
#include <memory>

#include <Eigen/Geometry>
#include <vector>

#include "fairshape/mesh/surface_mesh.h"

namespace fairshape {
class ClosestPointQuery;
}

namespace fairshape::feature {

struct SurfacePoint {
  int face = -1;
  Vec3 bary = Vec3::Zero();  // weights of the face's corners 0, 1, 2
};

class TriangleSurface {
 public:
  //! \throw InvalidInput when a face is not a triangle or `normals` has the wrong size.
  TriangleSurface(const SurfaceMesh& mesh, MatrixX3 vertex_normals);

  const SurfaceMesh& mesh() const { return *mesh_; }
  int n_faces() const { return static_cast<int>(corners_.size()); }
  const std::array<int, 3>& corners(int f) const { return corners_[f]; }
  //! The face across edge i of f (corners i, i + 1), −1 on the boundary.
  int across(int f, int i) const { return across_[f][i]; }
  Vec3 vertex(int v) const { return mesh_->position(v); }
  Vec3 vertex_normal(int v) const { return normals_.row(v).transpose(); }
  Vec3 face_normal(int f) const { return face_normals_.row(f).transpose(); }
  // The small queries below are inline: ray walks call them at every step.
  Vec3 point(const SurfacePoint& p) const {
    const auto& c = corners_[p.face];
    return p.bary[0] * vertex(c[0]) + p.bary[1] * vertex(c[1]) + p.bary[2] * vertex(c[2]);
  }
  //! Unit normal of the interpolated normal field at p.
  Vec3 normal(const SurfacePoint& p) const {
    const auto& c = corners_[p.face];
    const Vec3 n = p.bary[0] * vertex_normal(c[0]) + p.bary[1] * vertex_normal(c[1]) + p.bary[2] * vertex_normal(c[2]);
    const double len = n.norm();
    return len > 1e-300 ? Vec3(n / len) : face_normal(p.face);
  }
  //! Barycentric coordinates in f of a point of f's plane.
  Vec3 barycentric(int f, const Vec3& x) const {
    return Vec3(1.0, 0.0, 0.0) + barycentric_rate(f, x - vertex(corners_[f][0]));
  }
  //! Rate of change of the barycentric coordinates along an in-plane direction d of face f:
  //! d = a e1 + b e2 (e1 = p1 − p0, e2 = p2 − p0) by the normal equations.
  Vec3 barycentric_rate(int f, const Vec3& d) const {
    const auto& c = corners_[f];
    const Vec3 p0 = vertex(c[0]), e1 = vertex(c[1]) - p0, e2 = vertex(c[2]) - p0;
    const double g11 = e1.dot(e1), g12 = e1.dot(e2), g22 = e2.dot(e2);
    const double inv_det = 1 / (g11 * g22 - g12 * g12);
    const double r1 = e1.dot(d), r2 = e2.dot(d);
    const double a = (g22 * r1 - g12 * r2) * inv_det, b = (g11 * r2 - g12 * r1) * inv_det;
    return {-a - b, a, b};
  }
  //! The corner of f at vertex v, −1 if v is not a corner.
  int corner_of(int f, int v) const {
    const auto& c = corners_[f];
    return c[0] == v ? 0 : c[1] == v ? 1 : c[2] == v ? 2 : -1;
  }
  double longest_edge() const { return longest_edge_; }
  //! After the mesh's positions changed at `moved` (and nowhere else): the normals of `moved`
  //! and their one-ring (a limit normal reads the ring), the faces around `moved` and the longest
  //! edge become what a new TriangleSurface with loop_limit_normals would have (the same numbers);
  //! the closest-point tree is dropped. Costs the region, and a scan of the faces only when the
  //! longest edge may have shrunk.
  void refresh(const std::vector<int>& moved);
  //! The same surface on another mesh with the same connectivity and positions (a copy of it).
  void rebind(const SurfaceMesh& mesh) { mesh_ = &mesh; locator_.reset(); }
  //! Closest points on this level (a CGAL AABB tree, built on first use and kept).
  const ClosestPointQuery& locator() const;

 private:
  const SurfaceMesh* mesh_;
  MatrixX3 normals_, face_normals_;
  std::vector<std::array<int, 3>> corners_, across_;
  std::vector<double> face_longest_;
  double longest_edge_ = 0;
  mutable std::shared_ptr<const ClosestPointQuery> locator_;
};

//! The limit normals of a Loop level (the frame normals of the feature).
MatrixX3 loop_limit_normals(const SurfaceMesh& mesh);

}  // namespace fairshape::feature
