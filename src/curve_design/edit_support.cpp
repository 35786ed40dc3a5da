#include "fairshape/curve_design/edit_support.h"

namespace fairshape {

std::vector<char> edit_support(int n, bool closed, int levels, int e, const std::vector<int>& moved) {
  std::vector<char> inside(static_cast<std::size_t>(n), 0);
  const int stride = 1 << (levels - e);
  for (int i : moved)
    for (int k = (i - 1) * stride + 1; k < (i + 1) * stride; ++k) {
      if (closed) inside[static_cast<std::size_t>(((k % n) + n) % n)] = 1;
      else if (k >= 0 && k < n) inside[static_cast<std::size_t>(k)] = 1;
    }
  return inside;
}

double moved_outside_support(const MatrixX3& before, const MatrixX3& after, const std::vector<char>& support,
                             double tolerance) {
  int outside = 0, moved = 0;
  for (Eigen::Index i = 0; i < before.rows(); ++i) {
    if (support[static_cast<std::size_t>(i)]) continue;
    ++outside;
    moved += (after.row(i) - before.row(i)).norm() > tolerance;
  }
  return outside ? static_cast<double>(moved) / outside : 0.0;
}

double rounding_tolerance(const MatrixX3& X) {
  return 1e-12 * (X.colwise().maxCoeff() - X.colwise().minCoeff()).norm();
}

}  // namespace fairshape
