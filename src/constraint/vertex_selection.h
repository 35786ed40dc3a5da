// Which vertices a constraint applies to, as written in a config:
//   vertices: [12, 40]                     explicit ids
//   nearest: [x, y, z]                     the vertex closest to a point
//   region: {axis: x, from: 0.0, to: 0.3}  vertices whose coordinate along `axis` lies in a
//                                          fraction [from, to] of the bounding box
//   boundary_loop_near: [x, y, z]          the whole boundary loop with the boundary vertex
//                                          closest to a point (Figure 9's rotated inner rim)
#pragma once

#include <vector>

#include "fairshape/core/config.h"
#include "fairshape/mesh/surface_mesh.h"

namespace fairshape {

class VertexSelection {
 public:
  static VertexSelection from_config(Config& cfg);
  static VertexSelection vertices(std::vector<int> ids);
  static VertexSelection nearest(const Vec3& p);
  //! Vertices whose coordinate along axis (0, 1, 2) lies in [from, to] of the bounding box.
  static VertexSelection slab(int axis, double from, double to);
  static VertexSelection boundary_loop_near(const Vec3& p);
  //! \throw InvalidInput when an id is out of range or the selection is empty.
  std::vector<int> resolve(const SurfaceMesh& mesh, const std::string& who) const;

 private:
  std::vector<int> ids_;
  std::vector<double> nearest_, loop_near_;
  int axis_ = -1;
  double from_ = 0, to_ = 0;
};

}  // namespace fairshape
