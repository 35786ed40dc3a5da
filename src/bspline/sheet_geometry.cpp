#include "fairshape/bspline/sheet_geometry.h"

#include <Eigen/Geometry>

#include <cmath>

#include "fairshape/bspline/uniform_basis.h"

namespace fairshape::bspline {

Eigen::MatrixXd initial_coefficients(const SheetPlacement& s, const HierarchicalSurface& surface) {
  const SheetShape& shape = surface.shape();
  Eigen::MatrixXd P(surface.dof_count(), 3);
  const double shift = (shape.degree - 1) / 2.0;  // the Greville abscissa of control point i is i − shift
  const Vec3 a = s.u_axis.normalized(), n = s.v_axis.normalized();
  const Vec3 b = n.cross(a).normalized();
  for (int k = 0; k < surface.dof_count(); ++k) {
    const ControlId c = surface.dofs()[k];
    const double v = c.j - shift;
    if (s.geometry == SheetGeometry::Plane) {
      P.row(k) = (s.origin + (c.i - shift) * (s.size_u / shape.spans_u) * a + v * (s.size_v / shape.spans_v) * n).transpose();
    } else {
      const int m = shape.spans_u;
      const double theta = 2 * M_PI * (c.i - shift) / m;
      double blend = 0;  // the periodic B-spline's value at the node, relative to its control point
      const SpanBasis sb = uniform_span_basis(shape.degree, 0);
      for (int i = 0; i <= shape.degree; ++i) blend += sb.value[i] * std::cos(2 * M_PI * (i - shift) / m);
      const double radius = s.size_u / blend;
      P.row(k) = (s.origin + radius * (std::cos(theta) * a + std::sin(theta) * b) + v * (s.size_v / shape.spans_v) * n).transpose();
    }
  }
  return P;
}

SurfaceMesh tessellate(const HierarchicalSurface& s, const Eigen::MatrixXd& P, int per_span,
                       const HierarchicalSurface& initial_surface, const Eigen::MatrixXd& initial_P) {
  const bool periodic = s.shape().periodic_u;
  const int nu = s.shape().spans_u * per_span, nv = s.shape().spans_v * per_span;
  const int cols = periodic ? nu : nu + 1;
  MatrixX3 V(cols * (nv + 1), 3);
  Eigen::MatrixXd displacement(V.rows(), 3);  // from the initial sheet at the same (u, v)
  for (int i = 0; i < cols; ++i)
    for (int j = 0; j <= nv; ++j) {
      const double u = static_cast<double>(i) / per_span, v = static_cast<double>(j) / per_span;
      const Vec3 x = s.position(P, u, v);
      V.row(i * (nv + 1) + j) = x.transpose();
      displacement.row(i * (nv + 1) + j) = (x - initial_surface.position(initial_P, u, v)).transpose();
    }
  PolygonList faces;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const int i1 = periodic ? (i + 1) % nu : i + 1;
      faces.push_back({i * (nv + 1) + j, i1 * (nv + 1) + j, i1 * (nv + 1) + j + 1, i * (nv + 1) + j + 1});
    }
  SurfaceMesh m = SurfaceMesh::from_polygons(V, faces);
  m.vertex_data["displacement"] = displacement;
  m.vertex_data["displacement_norm"] = displacement.rowwise().norm();
  return m;
}

}  // namespace fairshape::bspline
