// A polyline: open or closed, 2D curves stored with z = 0.
#pragma once

#include "fairshape/core/types.h"

namespace fairshape {

struct Polyline {
  MatrixX3 points;
  bool closed = false;
  int n_points() const { return static_cast<int>(points.rows()); }
  int n_segments() const { return closed ? n_points() : n_points() - 1; }
};

}  // namespace fairshape
