// Wrinkles as numbers: the amplitude and wavelength of a known ripple, open and
// closed, in 3-D, invariant to rigid motions and proportional to scale.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "fairshape/curve_design/wrinkle_scale.h"

using namespace fairshape;

namespace {

constexpr double kPi = std::numbers::pi;

// A helix of n points (closed: a circle of radius 1 in a tilted plane) and the same curve with a
// ripple of amplitude A and `cycles` periods along it, across the curve.
struct Pair {
  MatrixX3 attracting, final;
};
Pair rippled(int n, bool closed, double A, int cycles) {
  Pair p{MatrixX3(n, 3), MatrixX3(n, 3)};
  for (int i = 0; i < n; ++i) {
    const double t = closed ? static_cast<double>(i) / n : static_cast<double>(i) / (n - 1);
    const double a = 2 * kPi * t;
    const Vec3 x = closed ? Vec3(std::cos(a), std::sin(a), 0.3 * std::sin(a)) : Vec3(std::cos(3 * a), std::sin(3 * a), 0.8 * t);
    const Vec3 across = closed ? Vec3(std::cos(a), std::sin(a), 0) : Vec3(std::cos(3 * a), std::sin(3 * a), 0);
    p.attracting.row(i) = x.transpose();
    p.final.row(i) = (x + A * std::sin(2 * kPi * cycles * t) * across).transpose();
  }
  return p;
}

}  // namespace

TEST_CASE("wrinkle scale: a known ripple's amplitude and wavelength, open and closed, in 3-D", "[curve][wrinkles]") {
  for (const bool closed : {false, true}) {
    for (const int cycles : {3, 8, 20}) {
      INFO((closed ? "closed" : "open") << ", " << cycles << " cycles");
      const Pair p = rippled(257, closed, 0.01, cycles);
      const WrinkleScale w = wrinkle_scale(p.final, p.attracting, closed);
      double L = 0;
      for (int i = 1; i < 257; ++i) L += (p.attracting.row(i) - p.attracting.row(i - 1)).norm();
      if (closed) L += (p.attracting.row(0) - p.attracting.row(256)).norm();
      CHECK(w.amplitude == Approx(0.01 / std::sqrt(2.0)).epsilon(0.03));
      // The arc length is not the parameter t the ripple was laid out in (the helix is uniform,
      // the tilted circle nearly so): the peak lands on the ripple's frequency.
      CHECK(w.wavelength == Approx(L / cycles).epsilon(0.05));
      CHECK(w.wavelength_segments == Approx((closed ? 257.0 : 256.0) / cycles).epsilon(0.05));
    }
  }
}

TEST_CASE("wrinkle scale: invariant to rigid motions, proportional to scale, zero without a change", "[curve][wrinkles]") {
  const Pair p = rippled(129, false, 0.02, 6);
  const WrinkleScale w = wrinkle_scale(p.final, p.attracting, false);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::RowVector3d shift(5, -2, 1);
  const WrinkleScale moved = wrinkle_scale((p.final * R.transpose()).rowwise() + shift, (p.attracting * R.transpose()).rowwise() + shift, false);
  CHECK(moved.amplitude == Approx(w.amplitude).epsilon(1e-9));
  CHECK(moved.wavelength == Approx(w.wavelength).epsilon(1e-9));
  const WrinkleScale scaled = wrinkle_scale(1000 * p.final, 1000 * p.attracting, false);
  CHECK(scaled.amplitude == Approx(1000 * w.amplitude).epsilon(1e-9));
  CHECK(scaled.wavelength == Approx(1000 * w.wavelength).epsilon(1e-9));
  CHECK(scaled.wavelength_segments == Approx(w.wavelength_segments).epsilon(1e-9));
  const WrinkleScale none = wrinkle_scale(p.attracting, p.attracting, false);
  CHECK(none.amplitude == 0);
  CHECK(none.wavelength == 0);
}
