// Building a symmetric sparse matrix row by row in parallel, straight into compressed storage:
// the Hessian gathered from per-vertex stencils (energy/gram_assembly) and the Galerkin
// product PᵀAP (solver/parallel_kernels). A dense accumulator per thread sums a row's
// contributions in the order gather() makes them, so the result is bitwise the same for any
// thread count; a pattern pass sizes the arrays, a value pass fills them (no triplets, no
// per-chunk buffers to join). Header-only; its users link TBB, in a build with it (without TBB,
// FAIRSHAPE_WITH_TBB=0, the rows are gathered serially by one accumulator: the same matrix).
#pragma once

#include "fairshape/core/backend.h"
#if FAIRSHAPE_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#endif

#include <algorithm>
#include <numeric>
#include <vector>

#include "fairshape/core/types.h"

namespace fairshape {

//! gather(i, add, values) calls add(col, value) for every contribution to row i, always in the
//! same order; `values` is false in the pattern pass, where the value is not read. The matrix
//! must be symmetric: its row-compressed arrays are returned as the column-compressed ones.
template <class Gather>
SparseMatrix assemble_symmetric_by_rows(int n, [[maybe_unused]] int grain, const Gather& gather) {
  struct Accumulator {
    std::vector<double> sum;
    std::vector<int> seen_in_row;
    std::vector<int> cols;
  };
#if FAIRSHAPE_WITH_TBB
  tbb::enumerable_thread_specific<Accumulator> accumulators(
      [n] { return Accumulator{std::vector<double>(n), std::vector<int>(n, -1), {}}; });
#else
  Accumulator serial{std::vector<double>(n), std::vector<int>(n, -1), {}};
#endif
  const auto gather_row = [&](int i, Accumulator& acc, bool values) {
    acc.cols.clear();
    gather(
        i,
        [&](int col, double value) {
          if (acc.seen_in_row[col] != i) {
            acc.seen_in_row[col] = i;
            acc.sum[col] = 0;
            acc.cols.push_back(col);
          }
          acc.sum[col] += value;
        },
        values);
  };
  SparseMatrix H(n, n);
  int* outer = H.outerIndexPtr();
  outer[0] = 0;
  const auto pattern_rows = [&](int begin, int end, Accumulator& acc) {
    for (int i = begin; i != end; ++i) {
      gather_row(i, acc, false);
      outer[i + 1] = static_cast<int>(acc.cols.size());
    }
  };
  const auto value_rows = [&](int begin, int end, Accumulator& acc) {
    for (int i = begin; i != end; ++i) {
      gather_row(i, acc, true);
      std::sort(acc.cols.begin(), acc.cols.end());
      int q = outer[i];
      for (int col : acc.cols) {
        H.innerIndexPtr()[q] = col;
        H.valuePtr()[q++] = acc.sum[col];
      }
    }
  };
#if FAIRSHAPE_WITH_TBB
  tbb::parallel_for(tbb::blocked_range<int>(0, n, grain),
                    [&](const tbb::blocked_range<int>& r) { pattern_rows(r.begin(), r.end(), accumulators.local()); });
  for (auto& acc : accumulators) std::fill(acc.seen_in_row.begin(), acc.seen_in_row.end(), -1);
#else
  pattern_rows(0, n, serial);
  std::fill(serial.seen_in_row.begin(), serial.seen_in_row.end(), -1);
#endif
  std::partial_sum(outer, outer + n + 1, outer);
  H.resizeNonZeros(outer[n]);
#if FAIRSHAPE_WITH_TBB
  tbb::parallel_for(tbb::blocked_range<int>(0, n, grain),
                    [&](const tbb::blocked_range<int>& r) { value_rows(r.begin(), r.end(), accumulators.local()); });
#else
  value_rows(0, n, serial);
#endif
  return H;
}

}  // namespace fairshape
