// Limit-surface evaluation at the vertices of a subdivision mesh: positions as a sparse
// operator (so constraints on the limit surface are linear rows) and tangent frames/normals.
#pragma once

#include "mesh/surface_mesh.h"
#include "subdivision/scheme.h"

namespace fairshape {

//! #V × #V: row v maps control points to the limit position of vertex v. Catmull-Clark
//! meshes with non-quad faces are refined once internally (the quad masks are then exact).
SparseMatrix limit_matrix(const SurfaceMesh& mesh, const SubdivisionOptions& opt);
MatrixX3 limit_positions(const SurfaceMesh& mesh, const SubdivisionOptions& opt);

//! Two tangents spanning the limit tangent plane at each vertex (not unit, not orthogonal).
//! Interior vertices of both schemes and Loop boundary vertices (Hoppe et al. 1994 masks);
//! vertices on a tagged crease: the bisector of the two sides' limit normals, t1 along the
//! crease; tagged corners: the angle-weighted face normal (no tangent plane there);
//! Catmull-Clark boundary vertices get the boundary-curve tangent and an across-tangent
//! from the adjacent faces' limit points (a documented approximation).
void limit_tangents(const SurfaceMesh& mesh, const SubdivisionOptions& opt, MatrixX3& t1, MatrixX3& t2);
//! Unit normals t1 × t2, oriented with the faces.
MatrixX3 limit_normals(const SurfaceMesh& mesh, const SubdivisionOptions& opt);

}  // namespace fairshape
