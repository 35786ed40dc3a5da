// B-splines on an arbitrary non-decreasing knot vector, clamped at both ends (Cox-de Boor):
// the multiplier space of a curve constraint (bspline/mortar_curve.h) lives on the knots where
// the curve crosses the surface's grid, which are not uniform; a curve constraint's target is
// a spline of this kind in t (a polyline: degree 1; a variational curve,
// bspline/variational_curve.h: its own degree on uniform knots).
#pragma once

#include <vector>

namespace fairshape::bspline {

class ClampedKnotBasis {
 public:
  //! Interior knots strictly inside (a, b), increasing; degree ≥ 0. The basis has
  //! interior.size() + degree + 1 functions on [a, b].
  ClampedKnotBasis(double a, double b, std::vector<double> interior, int degree);
  int size() const { return static_cast<int>(knots_.size()) - degree_ - 1; }
  int degree() const { return degree_; }
  //! The degree + 1 functions that may be nonzero at x ∈ [a, b]: their values and the index of
  //! the first (function first + k has value values[k]).
  void evaluate(double x, int& first, std::vector<double>& values) const;
  //! The values and first `order` derivatives (order ≤ degree) of the degree + 1 functions
  //! nonzero at x: ders[d][k] is the d-th derivative of function first + k.
  void derivatives(double x, int order, int& first, std::vector<std::vector<double>>& ders) const;
  //! ∫ of function j over [a, b]: (t_{j+r+1} − t_j) / (r + 1).
  double integral(int j) const;
  //! The distinct knots a, interior..., b: the breaks between which every function is one
  //! polynomial.
  std::vector<double> breaks() const;

 private:
  std::vector<double> knots_;
  int degree_;
};

}  // namespace fairshape::bspline
