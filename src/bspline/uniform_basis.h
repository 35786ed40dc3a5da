// Uniform B-spline blending functions and Gauss-Legendre rules: the one-dimensional pieces
// of Welch & Witkin's tensor-product spans (eq. 1 of "Variational surface modeling").
#pragma once

#include <array>
#include <vector>

namespace fairshape::bspline {

inline constexpr int kMinDegree = 2;  // the energies need second derivatives
inline constexpr int kMaxDegree = 5;
inline constexpr int kMaxOrder = kMaxDegree + 1;

//! The r+1 blending functions of one span at t ∈ [0, 1] and their first two derivatives in t.
//! Function i belongs to the control point i places after the span's first one.
struct SpanBasis {
  std::array<double, kMaxOrder> value{}, d1{}, d2{};
};
SpanBasis uniform_span_basis(int degree, double t);

//! The cardinal B-spline of degree r (support [0, r+1]) at x.
double cardinal_bspline(int degree, double x);

//! Refinement mask of a uniform B-spline of degree r: B(x) = Σ_k mask[k] B(2x − k), k = 0..r+1.
std::vector<double> refinement_mask(int degree);

struct GaussRule {
  std::vector<double> nodes, weights;  // on [0, 1]
};
//! n-point Gauss-Legendre on [0, 1], exact for polynomials of degree 2n − 1.
GaussRule gauss_legendre(int n);

}  // namespace fairshape::bspline
