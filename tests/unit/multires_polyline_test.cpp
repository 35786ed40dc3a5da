#include <catch2/catch.hpp>

#include "fairshape/curves/multires_polyline.h"

using namespace fairshape;

namespace {
Polyline random_curve(int n, bool closed, bool planar) {
  Polyline c;
  c.closed = closed;
  c.points = MatrixX3::Random(n, 3);
  if (planar) c.points.col(2).setZero();
  return c;
}
}  // namespace

TEST_CASE("lazy wavelets: decomposition then reconstruction is exact, both back ends", "[curves]") {
  for (bool closed : {false, true})
    for (bool planar : {true, false}) {
      const int n = closed ? 3 * 64 : 5 * 32 + 1;
      const Polyline c = random_curve(n, closed, planar);
      for (Backend b : {Backend::Reference, Backend::Optimized}) {
        const int levels = max_polyline_levels(n, closed);
        CHECK(levels == (closed ? 6 : 5));
        const PolylineHierarchy h = decompose(c, levels, b);
        CHECK(h.coarse.rows() == (closed ? 3 : 6));
        const Polyline back = reconstruct(h, levels, b);
        CHECK((back.points - c.points).cwiseAbs().maxCoeff() <= 1e-14);
        CHECK(back.closed == closed);
      }
      // Reference and optimized give identical coefficients.
      const auto r = decompose(c, 3, Backend::Reference), o = decompose(c, 3, Backend::Optimized);
      CHECK(r.coarse == o.coarse);
      for (int j = 0; j < 3; ++j) CHECK(r.details[j] == o.details[j]);
    }
}

TEST_CASE("lazy wavelets: coarse points are the even samples, details vanish on straight lines", "[curves]") {
  Polyline line;
  line.points.resize(17, 3);
  for (int i = 0; i < 17; ++i) line.points.row(i) << 0.5 * i, -2.0 * i, 0;
  const PolylineHierarchy h = decompose(line, 4, Backend::Reference);
  CHECK(h.coarse.rows() == 2);
  CHECK(h.coarse.row(1) == line.points.row(16));
  for (const auto& d : h.details) CHECK(d.cwiseAbs().maxCoeff() <= 1e-14);
  // A level in between is the subsampled curve.
  const Polyline mid = reconstruct(h, 2, Backend::Optimized);
  for (int i = 0; i < mid.n_points(); ++i) CHECK((mid.points.row(i) - line.points.row(4 * i)).norm() <= 1e-14);
}

TEST_CASE("lazy wavelets: invalid point counts and levels are refused with the valid forms", "[curves]") {
  CHECK_THROWS_WITH(decompose(random_curve(130, false, true), 1, Backend::Reference),
                    Catch::Matchers::Contains("2^n·k + 1 points"));
  CHECK_THROWS_WITH(decompose(random_curve(129, false, true), 8, Backend::Reference),
                    Catch::Matchers::Contains("allows 7 levels"));
  CHECK_THROWS_WITH(decompose(random_curve(12, true, true), 3, Backend::Reference),
                    Catch::Matchers::Contains("2^n·k points (k ≥ 3)"));
  const auto h = decompose(random_curve(9, false, true), 2, Backend::Reference);
  CHECK_THROWS_AS(reconstruct(h, 3, Backend::Reference), InvalidInput);
}
