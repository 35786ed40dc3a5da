// B-splines on an arbitrary non-decreasing knot vector, clamped at both ends or periodic (Cox-de Boor):
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
  //! The periodic basis on [a, b) (b ≡ a), one function per knot: `knots` in [a, b), increasing,
  //! at least degree + 1 of them (a closed curve's multipliers).
  static ClampedKnotBasis periodic(double a, double b, const std::vector<double>& knots, int degree);
  int size() const { return period_ > 0 ? period_ : static_cast<int>(knots_.size()) - degree_ - 1; }
  bool is_periodic() const { return period_ > 0; }
  int degree() const { return degree_; }
  //! The degree + 1 functions that may be nonzero at x ∈ [a, b]: their values and the index of
  //! the first (function first + k has value values[k]; periodic: (first + k) mod size()).
  void evaluate(double x, int& first, std::vector<double>& values) const;
  //! The values and first `order` derivatives (order ≤ degree) of the degree + 1 functions
  //! nonzero at x: ders[d][k] is the d-th derivative of function first + k. Clamped bases only.
  void derivatives(double x, int order, int& first, std::vector<std::vector<double>>& ders) const;
  //! ∫ of function j over [a, b]: (t_{j+r+1} − t_j) / (r + 1).
  double integral(int j) const;
  //! The distinct knots a, interior..., b: the breaks between which every function is one
  //! polynomial. Clamped bases only.
  std::vector<double> breaks() const;

 private:
  ClampedKnotBasis() = default;
  std::vector<double> knots_;
  int degree_ = 0;
  int period_ = 0;  // > 0: periodic, knots_ extended by `degree` on each side, functions mod period_
};

}  // namespace fairshape::bspline
