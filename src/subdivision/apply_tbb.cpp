#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "fairshape/subdivision/apply.h"

namespace fairshape {

void apply_stencils(const RowSparseMatrix& S, const MatrixX3& X, MatrixX3& Y) {
  Y.resize(S.rows(), 3);
  const int* outer = S.outerIndexPtr();
  const int* inner = S.innerIndexPtr();
  const double* w = S.valuePtr();
  const double* x = X.data();  // row-major: x, y, z of a vertex side by side
  double* y = Y.data();
  tbb::parallel_for(
      tbb::blocked_range<Eigen::Index>(0, S.rows(), 4096),
      [&](const tbb::blocked_range<Eigen::Index>& r) {
        for (Eigen::Index i = r.begin(); i != r.end(); ++i) {
          double a = 0, b = 0, c = 0;
          for (int k = outer[i]; k < outer[i + 1]; ++k) {
            const double* p = x + 3 * static_cast<std::ptrdiff_t>(inner[k]);
            a += w[k] * p[0];
            b += w[k] * p[1];
            c += w[k] * p[2];
          }
          y[3 * i] = a;
          y[3 * i + 1] = b;
          y[3 * i + 2] = c;
        }
      },
      tbb::static_partitioner());
}

}  // namespace fairshape
