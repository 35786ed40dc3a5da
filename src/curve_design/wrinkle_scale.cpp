#include "fairshape/curve_design/wrinkle_scale.h"

#include <Eigen/Geometry>
#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

namespace fairshape {

WrinkleScale wrinkle_scale(const MatrixX3& final, const MatrixX3& attracting, bool closed) {
  WrinkleScale out;
  const Eigen::Index n = attracting.rows();
  if (n < 4 || final.rows() != n) return out;
  // The change in a frame that turns with the curve (rotation-minimizing, by parallel transport
  // of a normal along the tangents): a ripple across a curved curve keeps its own frequency
  // instead of being modulated by the turning of fixed axes.
  MatrixX3 d = final - attracting;
  {
    const auto tangent = [&](Eigen::Index i) {
      const Eigen::Index a = i > 0 ? i - 1 : (closed ? n - 1 : 0), b = i + 1 < n ? i + 1 : (closed ? 0 : n - 1);
      return Vec3((attracting.row(b) - attracting.row(a)).transpose()).normalized();
    };
    Vec3 t = tangent(0);
    Vec3 u = t.unitOrthogonal();
    for (Eigen::Index i = 0; i < n; ++i) {
      const Vec3 next = tangent(i);
      u = Eigen::Quaterniond::FromTwoVectors(t, next) * u;  // transported: no twist about the curve
      u = (u - u.dot(next) * next).normalized();
      t = next;
      const Vec3 v = t.cross(u);
      const Vec3 di = d.row(i).transpose();
      d.row(i) << di.dot(t), di.dot(u), di.dot(v);
    }
  }
  out.amplitude = std::sqrt((d.rowwise() - d.colwise().mean()).rowwise().squaredNorm().mean());
  // Arc length of the attracting curve at each point (closed: the closing segment too).
  std::vector<double> s(static_cast<std::size_t>(n), 0.0);
  for (Eigen::Index i = 1; i < n; ++i) s[i] = s[i - 1] + (attracting.row(i) - attracting.row(i - 1)).norm();
  const double L = s.back() + (closed ? (attracting.row(0) - attracting.row(n - 1)).norm() : 0.0);
  const Eigen::Index segments = closed ? n : n - 1;
  if (!(L > 0) || !(out.amplitude > 0)) return out;
  // d at N points equally spaced in arc length (closed: periodic, the last sample before 0 again).
  // N: the power of two at or above n, so the FFT is O(N log N) for every n (a prime n made
  // Eigen's FFT quadratic: minutes at 131,073 points). The frequencies are cycles over L
  // whatever N, so the peak does not depend on it.
  Eigen::Index N = 1;
  while (N < n) N *= 2;
  // One pass: the samples' arc lengths increase, so the segment holding each one only moves on.
  MatrixX3 resampled(N, 3);
  std::size_t i = 0;
  for (Eigen::Index k = 0; k < N; ++k) {
    const double t = closed ? L * static_cast<double>(k) / static_cast<double>(N) : L * static_cast<double>(k) / static_cast<double>(N - 1);
    while (i + 1 < s.size() && s[i + 1] < t) ++i;
    const bool wraps = i + 1 == s.size();  // past the last point: the closing segment (closed) or the end
    const Eigen::Index j = wraps ? (closed ? 0 : static_cast<Eigen::Index>(i)) : static_cast<Eigen::Index>(i + 1);
    const double s1 = wraps ? L : s[i + 1];
    const double w = s1 > s[i] ? std::clamp((t - s[i]) / (s1 - s[i]), 0.0, 1.0) : 0.0;
    resampled.row(k) = (1 - w) * d.row(static_cast<Eigen::Index>(i)) + w * d.row(j);
  }
  std::vector<double> power(static_cast<std::size_t>(N / 2 + 1), 0.0);
  Eigen::FFT<double> fft;
  for (int c = 0; c < 3; ++c) {
    std::vector<double> x(static_cast<std::size_t>(N));
    for (Eigen::Index k = 0; k < N; ++k) x[k] = resampled(k, c);
    if (!closed) {
      // Detrend (least-squares line in k), then a Hann window.
      double mk = 0, mx = 0;
      for (Eigen::Index k = 0; k < N; ++k) mk += k, mx += x[k];
      mk /= N, mx /= N;
      double sxy = 0, sxx = 0;
      for (Eigen::Index k = 0; k < N; ++k) sxy += (k - mk) * (x[k] - mx), sxx += (k - mk) * (k - mk);
      const double slope = sxx > 0 ? sxy / sxx : 0;
      for (Eigen::Index k = 0; k < N; ++k)
        x[k] = (x[k] - mx - slope * (k - mk)) * 0.5 * (1 - std::cos(2 * std::numbers::pi * k / (N - 1)));
    }
    std::vector<std::complex<double>> X;
    fft.fwd(X, x);
    for (std::size_t k = 1; k < power.size(); ++k) power[k] += std::norm(X[k]);
  }
  std::size_t peak = 1;
  for (std::size_t k = 2; k < power.size(); ++k)
    if (power[k] > power[peak]) peak = k;
  // Frequency k: k cycles over the curve length L.
  out.wavelength = L / static_cast<double>(peak);
  out.wavelength_segments = out.wavelength / (L / static_cast<double>(segments));
  return out;
}

}  // namespace fairshape
