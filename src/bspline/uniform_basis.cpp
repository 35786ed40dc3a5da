#include "fairshape/bspline/uniform_basis.h"

#include <cmath>

#include "fairshape/core/error.h"

namespace fairshape::bspline {

double cardinal_bspline(int degree, double x) {
  if (x < 0 || x >= degree + 1) return 0;
  if (degree == 0) return 1;
  // Cox-de Boor on integer knots.
  return (x * cardinal_bspline(degree - 1, x) + (degree + 1 - x) * cardinal_bspline(degree - 1, x - 1)) / degree;
}

namespace {
// d/dx of the degree-r cardinal B-spline: M_{r−1}(x) − M_{r−1}(x − 1), applied `order` times.
double cardinal_derivative(int degree, double x, int order) {
  if (order == 0) return cardinal_bspline(degree, x);
  return cardinal_derivative(degree - 1, x, order - 1) - cardinal_derivative(degree - 1, x - 1, order - 1);
}
}  // namespace

SpanBasis uniform_span_basis(int degree, double t) {
  FAIRSHAPE_ASSERT(degree >= kMinDegree && degree <= kMaxDegree, "B-spline degree out of range");
  // At t = 1 the right-hand pieces are used; B-splines of degree r are C^{r−1}, so only the
  // second derivative of a quadratic differs there (a set of measure zero for the energies).
  SpanBasis b;
  for (int i = 0; i <= degree; ++i) {
    const double x = t + degree - i;
    b.value[i] = cardinal_bspline(degree, x);
    b.d1[i] = cardinal_derivative(degree, x, 1);
    b.d2[i] = cardinal_derivative(degree, x, 2);
  }
  return b;
}

std::vector<double> refinement_mask(int degree) {
  std::vector<double> mask(degree + 2);
  double binomial = 1;
  for (int k = 0; k <= degree + 1; ++k) {
    mask[k] = binomial / std::ldexp(1.0, degree);
    binomial = binomial * (degree + 1 - k) / (k + 1);
  }
  return mask;
}

GaussRule gauss_legendre(int n) {
  FAIRSHAPE_ASSERT(n >= 1 && n <= 16, "Gauss-Legendre order out of range");
  GaussRule rule;
  for (int i = 0; i < n; ++i) {
    // Newton on P_n from the Chebyshev-like initial guess.
    double x = std::cos(M_PI * (i + 0.75) / (n + 0.5));
    double derivative = 1;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      derivative = n * (x * p1 - p0) / (x * x - 1);
      const double dx = p1 / derivative;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    rule.nodes.push_back(0.5 * (1 - x));
    rule.weights.push_back(1.0 / ((1 - x * x) * derivative * derivative));  // 2/(…) halved for [0,1]
  }
  return rule;
}

}  // namespace fairshape::bspline
