// Sharp and semi-sharp creases and corners with OpenSubdiv's rules (its Sdc::Crease, the
// default "uniform" crease method), shared by every subdivision back end so that they agree.
//
// Sharpness lives on the mesh (SurfaceMesh::edge_sharpness / vertex_sharpness). On top of
// the tags, boundary edges are infinitely sharp and, with BoundaryMode::EdgeAndCorner, so is
// a boundary vertex with one face: the boundary rules are the crease and corner rules.
//
// A vertex's rule follows from its sharpness and its number of sharp edges: a sharp vertex
// or three or more sharp edges make a corner (it stays put), two a crease (cubic B-spline
// along the two sharp edges: 3/4, 1/8, 1/8), one a dart and none smooth (both the ordinary
// scheme mask). Each step lowers every finite sharpness by one (to 0 below 1); where the
// rule of the parent and of the child differ, the vertex point blends the two masks by the
// "fractional weight" (the mean of the sharpness values that decay to zero, clamped to 1).
// An edge point blends the midpoint (crease) and the smooth mask by the sharpness when it is
// below 1. Single-precision arithmetic for the sharpness values, as OpenSubdiv's.
#pragma once

#include <vector>

#include "mesh/surface_mesh.h"
#include "subdivision/scheme.h"

namespace fairshape {

inline constexpr float kInfiniteSharpness = 10.0f;  // OpenSubdiv's: 10 or more never decays

enum class VertexRule { Smooth, Dart, Crease, Corner };

//! One step's decay: infinite stays, s > 1 becomes s - 1, the rest 0 (the uniform method).
float decayed_sharpness(float s);
//! Tagged sharpness, infinite on boundary edges.
float effective_edge_sharpness(const SurfaceMesh& m, int e);
//! Tagged sharpness, infinite at a one-face boundary vertex under EdgeAndCorner.
float effective_vertex_sharpness(const SurfaceMesh& m, int v, BoundaryMode boundary);
VertexRule vertex_rule(float vertex_sharpness, int sharp_edges);
VertexRule vertex_rule(const SurfaceMesh& m, int v, BoundaryMode boundary);

//! The vertex point of v as a blend of three masks: the scheme's smooth mask, the crease
//! mask (3/4 v + 1/8 crease_a + 1/8 crease_b) and the corner mask (v). Weights sum to 1.
//! An interior vertex of an untagged mesh gets smooth = 1; a boundary vertex crease = 1 with
//! its two boundary neighbours, or corner = 1 (EdgeAndCorner, one face).
struct VertexMaskBlend {
  double smooth = 0, crease = 0, corner = 0;
  int crease_a = -1, crease_b = -1;
};
VertexMaskBlend vertex_mask_blend(const SurfaceMesh& m, int v, BoundaryMode boundary);

//! The two neighbours of v along its sharp edges (the first and last sharp edge counter-
//! clockwise from halfedge(v); on the boundary, the two boundary neighbours). False when v
//! does not have exactly two sharp edges.
bool crease_neighbours(const SurfaceMesh& m, int v, int& a, int& b);

//! Weight of the midpoint mask in the edge point of e (the smooth mask gets 1 minus it):
//! 0 for a smooth edge, 1 at sharpness >= 1 (and on the boundary), the sharpness between.
double edge_crease_weight(const SurfaceMesh& m, int e);

//! Sharpness of the child mesh of one refine_topology step: both halves of a parent edge get
//! its decayed sharpness, a vertex keeps its decayed sharpness, new edges and vertices are
//! smooth. Empty arrays when nothing stays sharp.
void child_sharpness(const SurfaceMesh& coarse, SurfaceMesh& fine);

//! Edges whose (effective) sharpness is > 0.
bool has_sharp_edges(const SurfaceMesh& m);

}  // namespace fairshape
