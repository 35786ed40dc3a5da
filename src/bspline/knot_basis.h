// B-splines on an arbitrary non-decreasing knot vector, clamped at both ends (Cox-de Boor):
// the multiplier space of a curve constraint (bspline/mortar_curve.h) lives on the knots where
// the curve crosses the surface's grid, which are not uniform.
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
  //! ∫ of function j over [a, b]: (t_{j+r+1} − t_j) / (r + 1).
  double integral(int j) const;

 private:
  std::vector<double> knots_;
  int degree_;
};

}  // namespace fairshape::bspline
