// The wave of data/curves/wave129.obj at any resolution 2^k + 1: the curve the Sauvage et al.
// benchmarks (curve_benchmark.cpp, curve_drag_benchmark.cpp) edit at every size.
#pragma once

#include <cmath>

#include "fairshape/mesh/polyline.h"

inline fairshape::Polyline curve_wave(int k) {
  const int n = (1 << k) + 1;
  fairshape::Polyline c;
  c.points.resize(n, 3);
  for (int i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / (n - 1);
    c.points.row(i) << 2 * t, 0.12 * std::sin(2 * M_PI * t) + 0.015 * std::sin(14 * M_PI * t), 0.0;
  }
  return c;
}
