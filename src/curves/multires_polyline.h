// Multiresolution polylines with the lazy-wavelet filter bank used by Sauvage, Hahmann and
// Bonneau, "Length preserving multiresolution editing of curves":
//   analysis   c^j_i = c^{j+1}_{2i},   d^j_i = c^{j+1}_{2i+1} − ½ (c^{j+1}_{2i} + c^{j+1}_{2i+2})
//   synthesis  c^{j+1}_{2i} = c^j_i,   c^{j+1}_{2i+1} = d^j_i + ½ (c^j_i + c^j_{i+1})
// Open curves of 2^n·k + 1 points and closed curves of 2^n·k points (indices wrap) decompose
// n levels. Points are rows (2D curves use z = 0; 3D works the same way).
#pragma once

#include <vector>

#include "fairshape/core/backend.h"
#include "fairshape/core/error.h"
#include "fairshape/mesh/polyline.h"

namespace fairshape {

struct PolylineHierarchy {
  bool closed = false;
  MatrixX3 coarse;               // c^0
  std::vector<MatrixX3> details;  // details[j] = d^j, j = 0 (coarsest) .. levels − 1
  int levels() const { return static_cast<int>(details.size()); }
};

//! How many levels a curve of n points allows (its k must stay ≥ 1 open, ≥ 3 closed).
int max_polyline_levels(int n_points, bool closed);
//! \throw InvalidInput when the point count does not allow `levels` levels (says which counts do).
PolylineHierarchy decompose(const Polyline& curve, int levels, Backend backend);
//! The curve at level j (0 = coarsest, levels() = the original resolution).
Polyline reconstruct(const PolylineHierarchy& h, int level, Backend backend);

// One filter-bank step, exposed for solvers that work level by level.
void analysis_step(const MatrixX3& fine, bool closed, MatrixX3& coarse, MatrixX3& detail, Backend backend);
MatrixX3 synthesis_step(const MatrixX3& coarse, const MatrixX3& detail, bool closed, Backend backend);
//! synthesis_step with zero details as a matrix (fine × coarse points): the prolongation of
//! a multilevel solver between polyline levels (solver/level_operators.h).
SparseMatrix synthesis_operator(int coarse_points, bool closed);

}  // namespace fairshape
