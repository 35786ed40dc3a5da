// A symmetric column-major matrix read as rows without a copy: for symmetric A the compressed
// columns are the compressed rows, so the same three arrays serve as both. At 4.5M unknowns
// every copy of the fine operator is ~0.9 GB; the multigrid set-up reads it as rows several
// times (ordering, renumbering, Galerkin product, patches).
#pragma once

#include "fairshape/core/error.h"
#include "fairshape/core/types.h"

namespace fairshape {

using RowSparseRef = Eigen::Ref<const RowSparseMatrix>;  // a row-major matrix or a view of one
using SymmetricRows = Eigen::Map<const RowSparseMatrix>;

//! A (compressed, symmetric: not checked) as a row-major matrix over A's own storage.
inline SymmetricRows rows_of_symmetric(const SparseMatrix& A) {
  FAIRSHAPE_ASSERT(A.isCompressed() && A.rows() == A.cols(), "rows_of_symmetric needs a compressed square matrix");
  return {A.rows(), A.cols(), A.nonZeros(), A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr()};
}

}  // namespace fairshape
