// A sparse Loop hierarchy for adaptive evaluation (Khodakovsky & Schröder, "Fine level feature
// editing for subdivision surfaces", §2.5: triangles are quadrisected only where needed). Each
// level holds a subset of the uniform level's faces, named by the ids the uniform refinement
// would give them (subdivision/subdivider.h, refine_topology_tbb.cpp: child faces 4f + j, edge
// points #V + e, the halves of half-edge h and the three interior edges in closed form), so a
// sparse vertex is the same vertex as in the uniform hierarchy and tests can compare them.
//
// Level k + 1 holds the children of the faces of level k chosen for refinement. A child's
// position is exact (equal to the uniform one) when every corner of its parent has its whole
// one-ring present on level k ("complete"): the Loop vertex point needs the ring, the edge point
// the two faces of the edge. Only such faces may be refined ("refinable"); the positions come
// from the project's own Loop rules (subdivide_positions_matrix_free) run on the level's faces
// as a patch mesh, of which only the exact children are kept.
#pragma once

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "fairshape/mesh/surface_mesh.h"
#include "fairshape/subdivision/scheme.h"

namespace fairshape::feature {

using UniformId = std::int64_t;

struct SparseLevel {
  int level = 0;
  UniformId n_vertices = 0, n_edges = 0, n_faces = 0;  // of the uniform level
  // Present faces: uniform id, uniform half-edges (edge i runs from corner i to corner i + 1,
  // half-edge 0 is the uniform face's first), bit i set when edge i lies on the uniform
  // boundary, corners as local vertex ids.
  std::vector<UniformId> face;
  std::vector<std::array<UniformId, 3>> halfedges;
  std::vector<std::uint8_t> on_boundary;
  std::vector<std::array<int, 3>> corners;
  // Local vertices: uniform id, number of faces around it in the uniform level, position.
  std::vector<UniformId> vertex;
  std::vector<int> faces_around;
  MatrixX3 positions;
  // The same vertices without any feature (the surface the finest/limit targets displace:
  // visible_profile.h); empty until a feature moved a coarser level (then equal to positions).
  MatrixX3 original;

  // Filled by index(): lookups and each vertex's present faces.
  std::unordered_map<UniformId, int> local_vertex, local_face, face_of_halfedge;
  std::vector<int> ring_start, ring_faces;  // CSR: present faces around local vertex v
  std::vector<char> complete;               // v's whole uniform one-ring is present

  void index();
  int n_local_faces() const { return static_cast<int>(face.size()); }
  int n_local_vertices() const { return static_cast<int>(vertex.size()); }
  int vertex_of(UniformId v) const { auto it = local_vertex.find(v); return it == local_vertex.end() ? -1 : it->second; }
  int face_of(UniformId f) const { auto it = local_face.find(f); return it == local_face.end() ? -1 : it->second; }
  //! The present face across edge i of local face f (−1: boundary or absent).
  int across(int f, int i) const;
  bool refinable(int f) const {
    return complete[corners[f][0]] && complete[corners[f][1]] && complete[corners[f][2]];
  }
  template <class F>
  void for_faces_around(int v, F f) const {
    for (int i = ring_start[v]; i < ring_start[v + 1]; ++i) f(ring_faces[i]);
  }
};

//! The whole base mesh as level 0 (every vertex complete). \throw InvalidInput unless triangles.
SparseLevel sparse_base_level(const SurfaceMesh& base);

//! The level's faces as a mesh for the Loop rules and the feature's walks: face i is present
//! face i, corners in the same order; an incomplete vertex whose present faces form several
//! fans gets one copy per fan (a mesh vertex must have one fan).
struct SparsePatch {
  SurfaceMesh mesh;
  std::vector<int> local;                    // patch vertex → local vertex
  std::vector<std::array<int, 3>> corners;   // patch vertex of each face corner
};
SparsePatch make_patch(const SparseLevel& level);

//! Level k + 1: the four children of each face in `refine` (local ids, each refinable), with
//! positions from one Loop step of the patch (`child_positions`, rows as
//! subdivide_positions_matrix_free numbers them); `child_original`, when given, the same step of
//! the positions without features (SparseLevel::original).
SparseLevel refine_sparse(const SparseLevel& level, const SparsePatch& patch, const MatrixX3& child_positions,
                          const std::vector<int>& refine, const MatrixX3* child_original = nullptr);

}  // namespace fairshape::feature
