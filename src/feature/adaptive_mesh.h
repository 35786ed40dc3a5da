// Adaptive Loop refinement (Khodakovsky & Schröder, "Fine level feature editing for subdivision
// surfaces", §2.5, Figure 13): a triangle of level k is quadrisected only where an edge midpoint
// (its level k + 1 vertex) leaves the plane of one of the two triangles sharing the edge by more
// than an angle, measured on the line from the midpoint to the triangle's opposite corner.
// Neighbouring triangles differ by at most one level, and a triangle next to finer ones is split
// into two or three (green closure), so the mesh is crack free. The levels come from a uniformly
// computed hierarchy (adaptive_evaluation.h computes only the refined region instead: far
// cheaper for local features on a fine level); refinement stops at its finest level. Every vertex
// takes its finest-level position.
#pragma once

#include <array>
#include <vector>

#include "fairshape/subdivision/multires_surface.h"

namespace fairshape::feature {

struct AdaptiveMesh {
  SurfaceMesh mesh;
  std::vector<int> finest_vertex;   // each vertex's id on the finest level
  std::vector<int> triangles_per_level;  // leaves by level (green triangles count on their level)
};

//! The triangles of a leaf with corners `corner` and, on its edge i (corner i → i + 1), the
//! midpoint mid[i] of a finer neighbour or −1: the leaf itself, or two or three green triangles.
//! \pre at most two midpoints (a leaf with three is split by the balancing).
std::vector<std::array<int, 3>> green_closure(const std::array<int, 3>& corner, const std::array<int, 3>& mid);

//! \throw InvalidInput for a non-Loop hierarchy, a level outside it or an angle outside (0, 90).
AdaptiveMesh adaptive_mesh(const MultiresSurface& surface, int from_level, double flatness_angle_deg);

}  // namespace fairshape::feature
