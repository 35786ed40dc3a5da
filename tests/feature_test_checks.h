// Checks the sparse-evaluation tests share (sparse_loop_test, sparse_features_test): one
// definition, so both compare the sparse and uniform measures by the same rule.
#pragma once

#include <catch2/catch.hpp>

#include <cmath>

#include "fairshape/feature/profile_measure.h"

namespace fairshape::test {

// Every number of two measures equal to `tol` (NaN on both sides counts as equal).
inline void check_same_measure(const feature::ProfileMeasure& a, const feature::ProfileMeasure& b, double tol,
                               const char* where) {
  const double x[] = {a.height_min, a.height_max, a.height_error, a.width_left, a.width_right, a.width_error, a.profile_error};
  const double y[] = {b.height_min, b.height_max, b.height_error, b.width_left, b.width_right, b.width_error, b.profile_error};
  for (int i = 0; i < 7; ++i) {
    INFO(where << " value " << i << ": sparse " << x[i] << ", uniform " << y[i]);
    CHECK((std::abs(x[i] - y[i]) <= tol || (std::isnan(x[i]) && std::isnan(y[i]))));
  }
}

}  // namespace fairshape::test
