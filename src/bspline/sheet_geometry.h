// Where a sheet starts and how it is drawn: the initial control points of a plane or a
// cylinder placed in the world, and the tessellation of a (refined) sheet into a quad mesh.
#pragma once

#include "fairshape/bspline/hierarchical_surface.h"
#include "fairshape/mesh/surface_mesh.h"

namespace fairshape::bspline {

enum class SheetGeometry { Plane, Cylinder };  // a cylinder is periodic in u

struct SheetPlacement {
  SheetGeometry geometry = SheetGeometry::Plane;
  Vec3 origin = Vec3::Zero();  // plane: the corner at (0, 0); cylinder: the center of the base circle
  Vec3 u_axis = Vec3::UnitX();  // plane: world direction of u; cylinder: the first radial axis
  Vec3 v_axis = Vec3::UnitY();  // world direction of v (the cylinder's axis)
  double size_u = 1, size_v = 1;  // plane: world extent; cylinder: radius (size_u) and height (size_v)
};

//! The control points of `surface` (unrefined) that make it the placed plane — exactly, by
//! the B-splines' linear precision at the Greville abscissae — or a cylinder whose periodic
//! curve passes through radius size_u at the control points' parameters.
Eigen::MatrixXd initial_coefficients(const SheetPlacement& placement, const HierarchicalSurface& surface);

//! The sheet sampled `per_span` times per base span as a quad mesh (seamless around a
//! cylinder), with the point array displacement_norm: |x(u, v) − x_initial(u, v)|.
SurfaceMesh tessellate(const HierarchicalSurface& surface, const Eigen::MatrixXd& P, int per_span,
                       const HierarchicalSurface& initial_surface, const Eigen::MatrixXd& initial_P);

}  // namespace fairshape::bspline
