// Closest points on a triangle mesh through a CGAL AABB tree (kept behind a pimpl: CGAL's
// headers cost ~10 s per translation unit).
#pragma once

#include <memory>
#include <vector>

#include "mesh/surface_mesh.h"

namespace fairshape {

class ClosestPointQuery {
 public:
  //! Polygons are split into triangle fans. \throw InvalidInput for an empty mesh.
  explicit ClosestPointQuery(const SurfaceMesh& surface);
  ~ClosestPointQuery();
  //! Closest surface point of every row of `points` (parallel over rows); with `faces`, also
  //! the face each one lies on.
  MatrixX3 closest_points(const MatrixX3& points, std::vector<int>* faces = nullptr) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fairshape
