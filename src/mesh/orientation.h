// Folds: where an edited surface turns over against the surface it was made from. A linear
// solve can meet every constraint and still fold — normal rows (tangents ⊥ N) hold for −N as
// well as N, and a small region asked to move far bends back on itself — so every surface run
// looks at its result with this check (configs/README.md, "flipped_faces").
#pragma once

#include <array>
#include <string>
#include <vector>

#include "fairshape/mesh/surface_mesh.h"

namespace fairshape {

//! Half the sum of p_i × p_{i+1} over the corners of face f at `positions` (Newell): the face's
//! normal scaled by its area, for planar and non-planar polygons alike.
Vec3 vector_area(const SurfaceMesh& mesh, const MatrixX3& positions, int f);

//! The area-weighted normal of the faces around vertex v at `positions` (zero where they cancel).
Vec3 area_normal(const SurfaceMesh& mesh, const MatrixX3& positions, int v);

struct FoldReport {
  int faces = 0;                 // faces compared (those with an area on both surfaces)
  std::vector<int> flipped;      // faces whose vector area points against their rest one's
  Vec3 center = Vec3::Zero();    // the mean centroid of the flipped faces on the result
  double largest_turn_deg = 0;   // the largest angle between a face's rest and result normals
  //! "421 of 36128 faces flipped, around (0.1, 0.2, 0.3)" (empty without a flip).
  std::string describe() const;
};

//! Compares every face of `mesh` at `result` with the same face at mesh.positions(). A face
//! whose rest or result area is below 1e-12 of the mean rest face area (degenerate) is skipped.
//! \throw InvalidInput if `result` does not have one row per vertex.
FoldReport flipped_faces(const SurfaceMesh& mesh, const MatrixX3& result);

//! flipped_faces against one rest surface for many results (a drag's steps): the rest faces'
//! vector areas are computed once, the result's in parallel.
class RestFaces {
 public:
  explicit RestFaces(const SurfaceMesh& mesh);
  //! flipped_faces(mesh, result), with the mesh this was built from.
  FoldReport compare(const MatrixX3& result) const;

 private:
  const SurfaceMesh& mesh_;
  std::vector<Vec3> areas_;
};

//! Sets `mesh`'s vertex array "flipped": 1 on the corners of the faces `folds` found turned
//! over, 0 elsewhere — where a fold is, for the viewer. `folds` must come from flipped_faces on
//! this mesh's topology.
void mark_flipped(SurfaceMesh& mesh, const FoldReport& folds);

//! The same comparison for triangles given by their corners, on a patch of a surface (the
//! present faces of a sparse level): `rest` and `result` hold the same vertices.
//! \throw InvalidInput for a corner out of range or position counts that differ.
FoldReport flipped_triangles(const std::vector<std::array<int, 3>>& triangles, const MatrixX3& rest, const MatrixX3& result);

}  // namespace fairshape
