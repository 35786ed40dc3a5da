// Closest points on a triangle mesh through a CGAL AABB tree (kept behind a pimpl: CGAL's
// headers cost ~10 s per translation unit).
#pragma once

#include <memory>
#include <vector>

#include "fairshape/mesh/surface_mesh.h"

namespace fairshape {

class ClosestPointQuery {
 public:
  //! Polygons are split into triangle fans. \throw InvalidInput for an empty mesh.
  explicit ClosestPointQuery(const SurfaceMesh& surface);
  ~ClosestPointQuery();
  //! Closest surface point of every row of `points` (parallel over rows); with `faces`, also
  //! the face each one lies on.
  MatrixX3 closest_points(const MatrixX3& points, std::vector<int>* faces = nullptr) const;
  //! Points moved along ±normals (one per row, any length) to the nearest crossing of the
  //! surface within `reach` on a face turned the same way. Closest points bunch up: every
  //! point in the normal cone of a convex vertex of the surface lands on that vertex, so
  //! neighbours collapse onto a horn tip; and they jump across thin parts (an ear, a finger)
  //! to the far side, folding a remesh. Normals of a smooth remesh vary slowly, so rays from
  //! neighbouring points land apart. A point with no such crossing takes its closest point;
  //! `*unmoved` counts those. With reach ≤ 0: plain closest points.
  MatrixX3 facing_points(const MatrixX3& points, const MatrixX3& normals, double reach, int* unmoved = nullptr) const;
  //! Per row: the distance from the point along its direction (any length) to the nearest
  //! crossing of the surface farther than `skip`; +infinity where the ray leaves the surface.
  Eigen::VectorXd ray_distances(const MatrixX3& points, const MatrixX3& directions, double skip) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fairshape
