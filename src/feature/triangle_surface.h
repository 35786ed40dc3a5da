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

#include "mesh/surface_mesh.h"

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
  Vec3 point(const SurfacePoint& p) const;
  //! Unit normal of the interpolated normal field at p.
  Vec3 normal(const SurfacePoint& p) const;
  //! Barycentric coordinates in f of a point of f's plane.
  Vec3 barycentric(int f, const Vec3& x) const;
  //! Rate of change of the barycentric coordinates along an in-plane direction d of face f.
  Vec3 barycentric_rate(int f, const Vec3& d) const;
  //! The corner of f at vertex v, −1 if v is not a corner.
  int corner_of(int f, int v) const;
  double longest_edge() const { return longest_edge_; }
  //! Closest points on this level (a CGAL AABB tree, built on first use and kept).
  const ClosestPointQuery& locator() const;

 private:
  const SurfaceMesh* mesh_;
  MatrixX3 normals_, face_normals_;
  std::vector<std::array<int, 3>> corners_, across_;
  double longest_edge_ = 0;
  mutable std::shared_ptr<const ClosestPointQuery> locator_;
};

//! The limit normals of a Loop level (the frame normals of the feature).
MatrixX3 loop_limit_normals(const SurfaceMesh& mesh);

}  // namespace fairshape::feature
