// How good a remesh is, as numbers a user can check: the two-sided Hausdorff distance between
// the remesh and the surface it replaces (sampled on both surfaces, not just at vertices: a
// remesh whose vertices all lie on the dense surface can still cut corners between them), the
// spread of edge lengths (divided differences scale like 1/h², so a short edge is what ruins
// the conditioning of fairness energies) and the valence histogram (irregular vertices are
// where subdivision is only C¹).
#pragma once

#include <map>
#include <string>

#include "fairshape/mesh/surface_mesh.h"

namespace fairshape {

class ClosestPointQuery;

//! Points on every face of `mesh` (polygons as triangle fans): the vertices, points along the
//! edges and a barycentric grid inside each triangle (at least its centroid), neighbouring
//! samples at most `spacing` apart; a point shared by faces is sampled once.
MatrixX3 sample_surface(const SurfaceMesh& mesh, double spacing);

struct SurfaceDistance {
  double a_to_b = 0, b_to_a = 0;  // largest distance of a sample of one surface to the other
  double hausdorff() const { return a_to_b > b_to_a ? a_to_b : b_to_a; }
};
//! Two-sided Hausdorff distance, sampled with `spacing` on both surfaces. Exact up to the sample
//! spacing: the true value lies within `spacing` of the result.
SurfaceDistance hausdorff_distance(const SurfaceMesh& a, const ClosestPointQuery& on_a, const SurfaceMesh& b,
                                   const ClosestPointQuery& on_b, double spacing);

struct EdgeLengthRange {
  double shortest = 0, longest = 0;
  int shortest_id = -1, longest_id = -1;  // the edges (SurfaceMesh edge ids)
  double ratio() const { return longest / shortest; }  // +inf for a collapsed edge
};
EdgeLengthRange edge_length_range(const SurfaceMesh& mesh);

//! valence -> number of vertices (isolated vertices are not counted).
using ValenceHistogram = std::map<int, int>;
ValenceHistogram valence_histogram(const SurfaceMesh& mesh);
//! "3:12 4:540 5:30", ascending valence.
std::string to_string(const ValenceHistogram& h);

double bounding_box_diagonal(const SurfaceMesh& mesh);

}  // namespace fairshape
