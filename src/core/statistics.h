// The summary statistics every timing repeat reports, defined once so all run kinds agree.
#pragma once

#include <algorithm>
#include <vector>

#include "fairshape/core/error.h"

namespace fairshape {

//! The median; for an even count, the mean of the two middle values.
inline double median(std::vector<double> v) {
  FAIRSHAPE_ASSERT(!v.empty(), "median of no values");
  const std::size_t n = v.size();
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n / 2), v.end());
  const double upper = v[n / 2];
  if (n % 2) return upper;
  const double lower = *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n / 2));
  return 0.5 * (lower + upper);
}

}  // namespace fairshape
