#include "fairshape/bspline/knot_basis.h"

#include <algorithm>
#include <cmath>

#include "fairshape/core/error.h"

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

void ClampedKnotBasis::derivatives(double x, int order, int& first, std::vector<std::vector<double>>& ders) const {
  const int r = degree_;
  FAIRSHAPE_ASSERT(order >= 0 && order <= r, "clamped knot basis: derivative order above the degree");
  FAIRSHAPE_ASSERT(period_ == 0, "knot basis derivatives: clamped bases only");
  const double a = knots_.front(), b = knots_.back();
  x = std::clamp(x, a, b);
  int s = static_cast<int>(std::upper_bound(knots_.begin(), knots_.end(), x) - knots_.begin()) - 1;
  s = std::min(s, static_cast<int>(knots_.size()) - r - 2);
  first = s - r;
  // The triangular table of every lower degree's functions (upper part) and knot differences
  // (lower part); the derivatives are differences of the lower degrees' functions (Piegl &
  // Tiller's scheme). On a non-empty interval [t_s, t_{s+1}) no difference used is zero.
  const auto R = static_cast<std::size_t>(r + 1);
  std::vector<std::vector<double>> ndu(R, std::vector<double>(R, 0.0));
  std::vector<double> left(R), right(R);
  ndu[0][0] = 1;
  for (int j = 1; j <= r; ++j) {
    left[j] = x - knots_[s + 1 - j];
    right[j] = knots_[s + j] - x;
    double saved = 0;
    for (int k = 0; k < j; ++k) {
      ndu[j][k] = right[k + 1] + left[j - k];
      const double temp = ndu[k][j - 1] / ndu[j][k];
      ndu[k][j] = saved + right[k + 1] * temp;
      saved = left[j - k] * temp;
    }
    ndu[j][j] = saved;
  }
  ders.assign(static_cast<std::size_t>(order + 1), std::vector<double>(R, 0.0));
  for (int j = 0; j <= r; ++j) ders[0][j] = ndu[j][r];
  std::vector<std::vector<double>> c(2, std::vector<double>(R, 0.0));
  for (int k = 0; k <= r; ++k) {
    int s1 = 0, s2 = 1;
    c[0][0] = 1;
    for (int d = 1; d <= order; ++d) {
      double sum = 0;
      const int rk = k - d, pk = r - d;
      if (k >= d) {
        c[s2][0] = c[s1][0] / ndu[pk + 1][rk];
        sum = c[s2][0] * ndu[rk][pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk, j2 = k - 1 <= pk ? d - 1 : r - k;
      for (int j = j1; j <= j2; ++j) {
        c[s2][j] = (c[s1][j] - c[s1][j - 1]) / ndu[pk + 1][rk + j];
        sum += c[s2][j] * ndu[rk + j][pk];
      }
      if (k <= pk) {
        c[s2][d] = -c[s1][d - 1] / ndu[pk + 1][k];
        sum += c[s2][d] * ndu[k][pk];
      }
      ders[d][k] = sum;
      std::swap(s1, s2);
    }
  }
  double factor = r;
  for (int d = 1; d <= order; ++d) {
    for (double& v : ders[d]) v *= factor;
    factor *= r - d;
  }
}

std::vector<double> ClampedKnotBasis::breaks() const {
  FAIRSHAPE_ASSERT(period_ == 0, "knot basis breaks: clamped bases only");
  std::vector<double> out;
  for (double k : knots_)
    if (out.empty() || k > out.back()) out.push_back(k);
  return out;
}

double ClampedKnotBasis::integral(int j) const {
  if (period_ > 0) j += degree_;  // periodic function j is extended function j + r
  return (knots_[j + degree_ + 1] - knots_[j]) / (degree_ + 1);
}

}  // namespace fairshape::bspline
