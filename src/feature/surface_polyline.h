// A polyline lying on one level of the hierarchy: straight pieces, each inside one face (a
// geodesic, a plane section). It is what the placement tools produce before it becomes a
// feature's control polygon; keeping the face of every piece lets it be cut, resampled and
// measured without ever leaving the surface.
#pragma once

#include <vector>

#include "fairshape/feature/ray_unrolling.h"

namespace fairshape::feature {

struct SurfacePolyline {
  std::vector<FacePiece> pieces;  // piece k ends where piece k + 1 starts
  bool closed = false;            // the last piece ends where the first starts
};

//! Length of each piece (world units) and their sum.
std::vector<double> piece_lengths(const TriangleSurface& s, const SurfacePolyline& line);
double polyline_length(const TriangleSurface& s, const SurfacePolyline& line);

//! The polyline's corners as a control polygon: every piece's start, and the last piece's end
//! unless closed (each point given in the face of the piece that leaves it).
std::vector<SurfacePoint> corner_points(const SurfacePolyline& line);

//! The point at arc length `arc` (clamped to the polyline, wrapped around when closed).
SurfacePoint point_at_arc(const TriangleSurface& s, const SurfacePolyline& line, double arc);

//! Arc length of the polyline's point closest to x.
double closest_arc(const TriangleSurface& s, const SurfacePolyline& line, const Vec3& x);

//! The part from arc length a to arc length b (a < b; on a closed polyline b may pass its
//! length, going on around the seam), as an open polyline.
SurfacePolyline between_arcs(const TriangleSurface& s, const SurfacePolyline& line, double a, double b);

//! Points along the polyline about `spacing` apart, evenly within each stretch between the
//! arc lengths `keep` (sorted), which are always samples; a closed polyline's samples do not
//! repeat the first one at the end. `fixed` (optional) marks the kept samples.
std::vector<SurfacePoint> resample(const TriangleSurface& s, const SurfacePolyline& line, double spacing,
                                   const std::vector<double>& keep, std::vector<char>* fixed = nullptr);

//! `iterations` steps of umbrella smoothing on the surface: every free point moves halfway to
//! the middle of its neighbours and back to its closest point on `s` (an open polygon keeps its
//! end points; `fixed` points stay). It rounds the kinks a path makes at mesh vertices.
void smooth_on_surface(const TriangleSurface& s, std::vector<SurfacePoint>& points, bool closed,
                       const std::vector<char>& fixed, int iterations);

}  // namespace fairshape::feature
