// Whether two sparse matrices have exactly the same entries: a design step that keeps the
// energy or the constraint rows, whose factorization a solver may keep (only f and b changed).
#pragma once

#include "fairshape/core/types.h"

namespace fairshape::qp {

inline bool same_matrix(const SparseMatrix& a, const SparseMatrix& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) return false;
  const SparseMatrix x = a - b;
  for (Eigen::Index i = 0; i < x.nonZeros(); ++i)
    if (x.valuePtr()[i] != 0) return false;
  return true;
}

}  // namespace fairshape::qp
