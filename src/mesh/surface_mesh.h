// Half-edge connectivity for manifold polygon meshes of any face size, with boundary and
// any genus, plus named per-vertex and per-face data arrays. Deliberately lean: topology,
// positions and properties only; algorithms are free functions elsewhere.
//
// Half-edges come in twin pairs (h, h ^ 1), so edge(h) = h / 2. A half-edge with face -1
// lies on a boundary loop. Vertex ids, face ids and the face-corner order of the input are
// kept, so ids are stable across read, process and write.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "fairshape/core/types.h"

namespace fairshape {

using PolygonList = std::vector<std::vector<int>>;

class SurfaceMesh {
 public:
  SurfaceMesh() = default;
  //! Builds and validates. \throw InvalidInput (empty, bad index, NaN/Inf coordinate, face with
  //! fewer than 3 or repeated vertices), TopologyError (non-manifold edge or vertex,
  //! inconsistent orientation). Messages name the offending face/vertex ids.
  static SurfaceMesh from_polygons(const MatrixX3& V, const PolygonList& faces);

  // Raw half-edge arrays of a mesh whose connectivity another algorithm derived (subdivision
  // builds child connectivity straight from the parent's). Trusted: only sizes are checked.
  struct HalfedgeArrays {
    std::vector<int> to_vertex, next, prev, face, vertex_halfedge, face_halfedge;
  };
  static SurfaceMesh from_halfedge_arrays(MatrixX3 V, HalfedgeArrays arrays);

  int n_vertices() const { return static_cast<int>(positions_.rows()); }
  int n_faces() const { return static_cast<int>(face_halfedge_.size()); }
  int n_edges() const { return static_cast<int>(to_vertex_.size() / 2); }
  int n_halfedges() const { return static_cast<int>(to_vertex_.size()); }

  // Half-edge navigation.
  int to_vertex(int h) const { return to_vertex_[h]; }
  int from_vertex(int h) const { return to_vertex_[h ^ 1]; }
  int twin(int h) const { return h ^ 1; }
  int next(int h) const { return next_[h]; }
  int prev(int h) const { return prev_[h]; }
  int face(int h) const { return face_[h]; }
  static int edge(int h) { return h >> 1; }
  bool is_boundary_halfedge(int h) const { return face_[h] < 0; }
  bool is_boundary_edge(int e) const { return face_[2 * e] < 0 || face_[2 * e + 1] < 0; }

  // Vertex queries. halfedge(v) is outgoing; on a boundary vertex it is the boundary one,
  // so a rotation started there visits the whole fan in order. -1 for an isolated vertex.
  int halfedge(int v) const { return vertex_halfedge_[v]; }
  bool is_isolated(int v) const { return vertex_halfedge_[v] < 0; }
  bool is_boundary_vertex(int v) const;
  int valence(int v) const;  // number of incident edges
  // Next outgoing half-edge counter-clockwise around from_vertex(h).
  int rotate_ccw(int h) const { return twin(prev_[h]); }
  std::vector<int> outgoing_halfedges(int v) const;  // ccw, starting at halfedge(v)
  //! f(h) for each outgoing half-edge of v in the same order, without allocating (hot loops).
  template <class F>
  void for_each_outgoing(int v, F&& f) const {
    const int start = vertex_halfedge_[v];
    if (start < 0) return;
    int h = start;
    do {
      f(h);
      h = rotate_ccw(h);
    } while (h != start);
  }
  std::vector<int> vertex_neighbors(int v) const;    // edge neighbours, same order
  std::vector<int> vertex_faces(int v) const;        // incident faces, same order

  // Face queries.
  int face_halfedge(int f) const { return face_halfedge_[f]; }
  int face_size(int f) const;
  std::vector<int> face_vertices(int f) const;  // in input corner order
  PolygonList polygons() const;

  // Boundary loops, each a list of vertex ids in the order of its boundary half-edges.
  std::vector<std::vector<int>> boundary_loops() const;

  MatrixX3& positions() { return positions_; }
  const MatrixX3& positions() const { return positions_; }
  Vec3 position(int v) const { return positions_.row(v).transpose(); }

  // Named data arrays ("v:displacement", "f:feature"): rows = #V or #F, any column count.
  std::map<std::string, Eigen::MatrixXd> vertex_data, face_data;

  // Crease and corner sharpness with OpenSubdiv's meaning: 0 is smooth, a value s in (0, 10)
  // keeps the sharp rule for about s levels, 10 or more is infinitely sharp. Kept in single
  // precision because OpenSubdiv stores and blends sharpness as float: the same floats give
  // the same fractional blend weights (and so agreement to 1e-12). Empty arrays: untagged.
  float edge_sharpness(int e) const { return edge_sharpness_.empty() ? 0.0f : edge_sharpness_[e]; }
  float vertex_sharpness(int v) const { return vertex_sharpness_.empty() ? 0.0f : vertex_sharpness_[v]; }
  bool has_sharpness() const { return !edge_sharpness_.empty() || !vertex_sharpness_.empty(); }
  const std::vector<float>& edge_sharpness_array() const { return edge_sharpness_; }
  const std::vector<float>& vertex_sharpness_array() const { return vertex_sharpness_; }
  //! The edge joining vertices a and b, or -1.
  int find_edge(int a, int b) const;
  //! \throw InvalidInput when a-b is not an edge of the mesh, or s is negative or not finite.
  void set_edge_sharpness(int a, int b, double s);
  //! \throw InvalidInput for a vertex id out of range, or s negative or not finite.
  void set_vertex_sharpness(int v, double s);
  //! Whole arrays (#E and #V entries, or empty), as subdivision hands them to the child mesh.
  //! \throw InvalidInput on a size mismatch.
  void set_sharpness(std::vector<float> edges, std::vector<float> vertices);

 private:
  MatrixX3 positions_;
  std::vector<int> to_vertex_, next_, prev_, face_;
  std::vector<int> vertex_halfedge_, face_halfedge_;
  std::vector<float> edge_sharpness_, vertex_sharpness_;
};

}  // namespace fairshape
