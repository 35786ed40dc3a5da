// The intersection of one level of the hierarchy with a plane, as polylines on the surface: a
// feature curve placed by a cut (a ridge around a body, a groove along a symmetry plane).
#pragma once

#include <vector>

#include "fairshape/feature/surface_polyline.h"

namespace fairshape::feature {

//! Every connected curve in which the plane through `point` with normal `normal` (any length
//! > 0) cuts `s`: closed loops, and open curves from boundary to boundary. Each runs the way
//! normal × (surface normal) points: seen from the normal's side, a loop around the outside of
//! a body turns counter-clockwise, one around a hole (the inner circle of a torus) clockwise.
//! A vertex lying on the plane counts as above it (so every crossed face holds one straight
//! piece). Empty when the plane misses the surface.
std::vector<SurfacePolyline> plane_section(const TriangleSurface& s, const Vec3& point, const Vec3& normal);

}  // namespace fairshape::feature
