// Shortest paths on one level of the hierarchy (exact polyhedral geodesics, CGAL's
// Surface_mesh_shortest_path) through a sequence of waypoints: a way to draw a feature curve on
// the surface by naming only the points it must pass (Khodakovsky & Schröder, "Fine level feature
// editing for subdivision surfaces", §1.4: the user draws on the surface of the chosen level).
#pragma once

#include <vector>

#include "fairshape/feature/surface_polyline.h"

namespace fairshape::feature {

struct GeodesicPath {
  SurfacePolyline line;
  std::vector<double> waypoint_arcs;  // arc length of each waypoint along `line`
};

//! The shortest path on `s` from each waypoint to the next (and from the last back to the first
//! when `closed`), joined. The path is straight inside every face and bends only at vertices.
//! \throw InvalidInput naming the waypoints (by index) when two lie on different connected
//! components of `s`, or when fewer than 2 (closed: 3) are given.
GeodesicPath geodesic_through(const TriangleSurface& s, const std::vector<SurfacePoint>& waypoints, bool closed);

//! Connected component of every face (through shared edges), numbered from 0.
std::vector<int> face_components(const TriangleSurface& s);

}  // namespace fairshape::feature
