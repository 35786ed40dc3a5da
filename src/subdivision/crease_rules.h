// Sharp and semi-sharp creases and corners with OpenSubdiv's rules (its Sdc::Crease, both
// crease methods: "uniform" and "chaikin"), shared by every subdivision back end so that they
// agree.
//
// Sharpness lives on the mesh (SurfaceMesh::edge_sharpness / vertex_sharpness). On top of
// the tags, boundary edges are infinitely sharp and, with BoundaryMode::EdgeAndCorner, so is
// a boundary vertex with one face: the boundary rules are the crease and corner rules.
//
// A vertex's rule follows from its sharpness and its number of sharp edges: a sharp vertex
// or three or more sharp edges make a corner (it stays put), two a crease (cubic B-spline
// along the two sharp edges: 3/4, 1/8, 1/8), one a dart and none smooth (both the ordinary
// scheme mask). Each step lowers every finite sharpness by one (to 0 below 1); with the
// Chaikin method a semi-sharp edge is first averaged with the other semi-sharp edges at the
// vertex its child half touches (3/4 its own, 1/4 their mean), so the two halves of an edge
// may differ. Where the rule of the parent and of the child differ, the vertex point blends
// the two masks by the "fractional weight" (the mean of the sharpness values that decay to
// zero, clamped to 1). An edge point is the midpoint (crease) while both child halves stay
// sharp, otherwise it blends midpoint and smooth mask by the edge's sharpness. Single-
// precision arithmetic for the sharpness values, as OpenSubdiv's.
#pragma once

#include <vector>

#include "fairshape/mesh/surface_mesh.h"
#include "fairshape/subdivision/scheme.h"

namespace fairshape {

inline constexpr float kInfiniteSharpness = 10.0f;  // OpenSubdiv's: 10 or more never decays

enum class VertexRule { Smooth, Dart, Crease, Corner };

//! One step's decay: infinite stays, s > 1 becomes s - 1, the rest 0 (the uniform method).
float decayed_sharpness(float s);
//! One step of the sharpness of the edges around one vertex (`parent` in the vertex's edge
//! order, boundary edges infinite): the child half of each edge at that vertex.
std::vector<float> child_sharpness_around(const std::vector<float>& parent, CreaseMethod method);
//! The child half of edge e at its end v (e's effective sharpness, decayed by `method`).
float child_edge_sharpness(const SurfaceMesh& m, int e, int v, CreaseMethod method);
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
VertexMaskBlend vertex_mask_blend(const SurfaceMesh& m, int v, BoundaryMode boundary, CreaseMethod method);

//! The two neighbours of v along its sharp edges (the first and last sharp edge counter-
//! clockwise from halfedge(v); on the boundary, the two boundary neighbours). False when v
//! does not have exactly two sharp edges.
bool crease_neighbours(const SurfaceMesh& m, int v, int& a, int& b);

//! Weight of the midpoint mask in the edge point of e (the smooth mask gets 1 minus it):
//! 0 for a smooth edge, 1 while both child halves stay sharp (and on the boundary),
//! otherwise the edge's sharpness: below 1 with the uniform method; the Chaikin method can
//! end a crease from a sharpness above 1, and OpenSubdiv then uses that sharpness unclamped
//! (an extrapolating blend), which we follow so that the surfaces agree.
double edge_crease_weight(const SurfaceMesh& m, int e, CreaseMethod method);

//! Sharpness of the child mesh of one refine_topology step: each half of a parent edge gets
//! the sharpness child_edge_sharpness gives at the parent vertex it touches (uniform: both
//! the decayed sharpness), a vertex keeps its decayed sharpness, new edges and vertices are
//! smooth. Empty arrays when nothing stays sharp.
void child_sharpness(const SurfaceMesh& coarse, SurfaceMesh& fine, CreaseMethod method);

//! Edges whose (effective) sharpness is > 0.
bool has_sharp_edges(const SurfaceMesh& m);

}  // namespace fairshape
