// Curves sampled into points equally spaced in their parameter t ∈ [0, 1]: the form in which
// the sheet constraints take curves (a curve constraint pairs its (u, v) polyline and its space
// curve point by point in t). Points are the rows of an n × d matrix: d = 2 for curves in a
// sheet's parameter plane, 3 for space curves. A closed curve ends where it starts (its last
// row repeats the first), so a consumer walking an open polyline from t = 0 to 1 goes round.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace fairshape {

//! `samples` points equally spaced in arc length along the polyline through the rows of
//! `vertices` (closed: plus the segment from the last row back to the first). Arc length is a
//! polyline's natural parameter: equal steps in t are equal distances along the path, however
//! unevenly the vertices are spaced. Every point lies on the path; a corner that falls between
//! two samples is cut, so give enough samples to follow corners.
//! Requires two vertices (closed: three), a path of positive length, samples ≥ 2 (closed: ≥ 4).
Eigen::MatrixXd resample_polyline(const Eigen::MatrixXd& vertices, bool closed, int samples);

//! center + radius (cos a e1 + sin a e2) for a from from_deg to to_deg (degrees; to < from
//! turns the other way). e1 and e2 are orthonormal and of the center's dimension.
struct CircleArc {
  Eigen::VectorXd center, e1, e2;
  double radius = 1, from_deg = 0, to_deg = 360;
  bool full_circle() const;  // |to − from| = 360: a closed curve
};
//! `samples` points equally spaced in angle, hence in arc length; a full circle's last point is
//! its first. Requires samples ≥ 2 (full circle: ≥ 4).
Eigen::MatrixXd sample_arc(const CircleArc& arc, int samples);

//! A B-spline curve of `degree` over control points (rows) and knots (rows + degree + 1,
//! non-decreasing); its parameter domain is [knots[degree], knots[rows]].
struct BSplineCurve {
  int degree = 3;
  Eigen::MatrixXd control;
  std::vector<double> knots;
  bool closed = false;  // periodic: the curve ends at its start point
};
//! Knots 0 (degree + 1 times), evenly spaced interior knots, 1 (degree + 1 times): the curve
//! starts at the first control point and ends at the last.
std::vector<double> uniform_clamped_knots(int control_points, int degree);
//! The closed uniform B-spline of the control polygon taken as a loop: control points wrap
//! round and the knots are evenly spaced (no clamping, so no corner where the loop closes).
//! t = 0 is where the first control point weighs most.
BSplineCurve periodic_bspline(const Eigen::MatrixXd& control, int degree);
//! Why the knots do not fit (empty when they do): count, order, an empty domain, or a knot
//! repeated so often that the curve would break apart.
std::string bspline_knot_problem(int control_points, int degree, const std::vector<double>& knots);
//! The curve point at parameter x of the knot domain (de Boor's algorithm).
Eigen::VectorXd bspline_point(const BSplineCurve& curve, double x);
//! `samples` points at equally spaced parameters of the knot domain: t is the B-spline's own
//! parameter mapped onto [0, 1], not its arc length (the two agree only for uniform speed).
Eigen::MatrixXd sample_bspline(const BSplineCurve& curve, int samples);

}  // namespace fairshape
