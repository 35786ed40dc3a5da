#include "bspline/knot_basis.h"

#include <algorithm>
#include <cmath>

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

ClampedKnotBasis ClampedKnotBasis::periodic(double a, double b, const std::vector<double>& knots, int degree) {
  const int n = static_cast<int>(knots.size());
  FAIRSHAPE_ASSERT(degree >= 0 && b > a && n >= degree + 1, "periodic knot basis: degree + 1 knots in [a, b)");
  ClampedKnotBasis out;
  out.degree_ = degree;
  out.period_ = n;
  // t_{j+n} = t_j + (b − a): `degree` knots before the first and degree + 1 after the last.
  const double L = b - a;
  for (int j = -degree; j < n + degree + 1; ++j) {
    const int k = ((j % n) + n) % n;
    out.knots_.push_back(knots[static_cast<std::size_t>(k)] + L * static_cast<double>((j - k) / n));
  }
  return out;
}

void ClampedKnotBasis::evaluate(double x, int& first, std::vector<double>& values) const {
  const int r = degree_;
  double a = knots_.front(), b = knots_.back();
  if (period_ > 0) {
    // Into [t_0, t_0 + L): the interval of the extended knots that holds x.
    a = knots_[static_cast<std::size_t>(r)];
    const double L = knots_[static_cast<std::size_t>(r + period_)] - a;
    x = a + std::fmod(std::fmod(x - a, L) + L, L);
    b = a + L;
  }
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
  if (period_ > 0) {
    // Extended function e is periodic function (e − r) mod n: rotate so values[k] belongs to
    // first + k, first in [0, n) (callers wrap first + k themselves).
    first = ((first - r) % period_ + period_) % period_;
  }
}

double ClampedKnotBasis::integral(int j) const {
  if (period_ > 0) j += degree_;  // periodic function j is extended function j + r
  return (knots_[j + degree_ + 1] - knots_[j]) / (degree_ + 1);
}

}  // namespace fairshape::bspline
