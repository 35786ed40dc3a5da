// Row kernels of the optimized iterative solvers on a compressed row-major matrix and row-major
// blocks of 1 to 3 columns (the x, y, z of one unknown side by side). These loops are the
// hot loops of every iterative solver: Eigen's InnerIterator plus a run-time column count
// cost ~15 cycles per entry where the memory system allows ~3 (perf on the level-3 cow
// sweep, session 9), so they work on raw arrays with the column count as a template argument.
#pragma once

#include <cstddef>
#include <type_traits>

#include "fairshape/core/error.h"
#include "fairshape/core/types.h"

namespace fairshape {

// A compressed row-major matrix as raw arrays.
struct CsrView {
  const int* outer;
  const int* inner;
  const double* value;
  explicit CsrView(const RowSparseMatrix& A)
      : outer(A.outerIndexPtr()), inner(A.innerIndexPtr()), value(A.valuePtr()) {
    FAIRSHAPE_ASSERT(A.isCompressed(), "row kernels need a compressed matrix");
  }
};

// s = Σ_j a_ij x_j over row i, for C columns of a row-major x. Two banks of sums break the
// chain of dependent multiply-adds (the entries' latency, not memory, bounded one bank).
template <int C>
inline void row_sum(const CsrView& A, Eigen::Index i, const double* x, double (&s)[C]) {
  double even[C] = {}, odd[C] = {};
  int k = A.outer[i];
  const int end = A.outer[i + 1];
  for (; k + 1 < end; k += 2) {
    const double* x0 = x + static_cast<std::ptrdiff_t>(A.inner[k]) * C;
    const double* x1 = x + static_cast<std::ptrdiff_t>(A.inner[k + 1]) * C;
    for (int c = 0; c < C; ++c) {
      even[c] += A.value[k] * x0[c];
      odd[c] += A.value[k + 1] * x1[c];
    }
  }
  if (k < end)
    for (int c = 0; c < C; ++c) even[c] += A.value[k] * x[static_cast<std::ptrdiff_t>(A.inner[k]) * C + c];
  for (int c = 0; c < C; ++c) s[c] = even[c] + odd[c];
}

// Calls f(std::integral_constant<int, C>) for the block's column count C ∈ {1, 2, 3}.
template <class F>
void with_columns(Eigen::Index cols, const F& f) {
  switch (cols) {
    case 1: return f(std::integral_constant<int, 1>());
    case 2: return f(std::integral_constant<int, 2>());
    case 3: return f(std::integral_constant<int, 3>());
    default: FAIRSHAPE_ASSERT(false, "row kernels take 1 to 3 columns");
  }
}

}  // namespace fairshape
