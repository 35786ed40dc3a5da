// Limit-surface evaluation at the vertices of a subdivision mesh: positions as a sparse
// operator (so constraints on the limit surface are linear rows) and tangent frames/normals.
#pragma once

#include "fairshape/mesh/surface_mesh.h"
#include "fairshape/subdivision/scheme.h"

namespace fairshape {

//! #V × #V: row v maps control points to the limit position of vertex v. Catmull-Clark
//! meshes with non-quad faces are refined once internally (the quad masks are then exact).
SparseMatrix limit_matrix(const SurfaceMesh& mesh, const SubdivisionOptions& opt);
MatrixX3 limit_positions(const SurfaceMesh& mesh, const SubdivisionOptions& opt);

//! Whether row v of limit_matrix is the exact limit of the surface: a vertex whose edges are
//! all smooth (its one-ring subdivides by the smooth rules forever), a vertex on two or more
//! infinitely sharp edges (a crease is a cubic B-spline, three make a corner), an infinitely
//! sharp corner. At a dart (one sharp edge) or where a semi-sharp tag at or around v has not
//! decayed yet the rules around v change in later steps, which a mask of this level cannot
//! know: the row is then an approximation, as OpenSubdiv's Far::PrimvarRefiner::Limit() is
//! (they agree); LimitEvaluator (Bfr) refines those features away and is exact.
bool vertex_limit_mask_exact(const SurfaceMesh& mesh, int v);

//! Two tangents spanning the limit tangent plane at each vertex (not unit, not orthogonal).
//! Interior vertices of both schemes and Loop boundary vertices (Hoppe et al. 1994 masks);
//! vertices on a tagged crease: the bisector of the two sides' limit normals, t1 along the
//! crease; tagged corners: the angle-weighted face normal (no tangent plane there);
//! Catmull-Clark boundary vertices get the boundary-curve tangent and an across-tangent
//! from the adjacent faces' limit points (a documented approximation).
void limit_tangents(const SurfaceMesh& mesh, const SubdivisionOptions& opt, MatrixX3& t1, MatrixX3& t2);
//! Unit normals t1 × t2, oriented with the faces.
MatrixX3 limit_normals(const SurfaceMesh& mesh, const SubdivisionOptions& opt);
//! Row v of limit_normals (the same numbers), for updating a few vertices of a large mesh.
//! \throw InvalidInput for a Catmull-Clark mesh with non-quad faces (refined internally there).
Vec3 limit_normal_at(const SurfaceMesh& mesh, const SubdivisionOptions& opt, int v);

}  // namespace fairshape
