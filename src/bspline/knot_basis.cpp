#include "bspline/knot_basis.h"

#include <algorithm>

#include "core/error.h"

namespace fairshape::bspline {

ClampedKnotBasis::ClampedKnotBasis(double a, double b, std::vector<double> interior, int degree) : degree_(degree) {
  FAIRSHAPE_ASSERT(degree >= 0 && b > a, "clamped knot basis: degree >= 0 and a < b");
  knots_.assign(static_cast<std::size_t>(degree + 1), a);
  for (double k : interior) {
    FAIRSHAPE_ASSERT(k > knots_.back() && k < b, "clamped knot basis: interior knots increasing inside (a, b)");
    knots_.push_back(k);
  }
  knots_.insert(knots_.end(), static_cast<std::size_t>(degree + 1), b);
}

void ClampedKnotBasis::evaluate(double x, int& first, std::vector<double>& values) const {
  const int r = degree_;
  const double a = knots_.front(), b = knots_.back();
  x = std::clamp(x, a, b);
  // The knot interval [t_s, t_{s+1}) holding x (the last non-empty one at x = b).
  int s = static_cast<int>(std::upper_bound(knots_.begin(), knots_.end(), x) - knots_.begin()) - 1;
  s = std::min(s, static_cast<int>(knots_.size()) - r - 2);
  // Cox-de Boor, the triangular scheme on the r + 1 functions nonzero there.
  values.assign(static_cast<std::size_t>(r + 1), 0.0);
  values[0] = 1;
  std::vector<double> left(static_cast<std::size_t>(r + 1)), right(static_cast<std::size_t>(r + 1));
  for (int j = 1; j <= r; ++j) {
    left[j] = x - knots_[s + 1 - j];
    right[j] = knots_[s + j] - x;
    double saved = 0;
    for (int k = 0; k < j; ++k) {
      const double denom = right[k + 1] + left[j - k];
      const double temp = denom > 0 ? values[k] / denom : 0.0;
      values[k] = saved + right[k + 1] * temp;
      saved = left[j - k] * temp;
    }
    values[j] = saved;
  }
  first = s - r;
}

double ClampedKnotBasis::integral(int j) const {
  return (knots_[j + degree_ + 1] - knots_[j]) / (degree_ + 1);
}

}  // namespace fairshape::bspline
