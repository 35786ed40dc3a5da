#include "fairshape/io/finite_output.h"

#include <cmath>
#include <cstdio>

#include "fairshape/core/error.h"

namespace fairshape::io::internal {
namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

void require_finite(const Eigen::Ref<const Eigen::MatrixXd>& m, const std::string& path, const std::string& row_name) {
  if (m.allFinite()) return;
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    if (m.row(r).allFinite()) continue;
    std::string values;
    for (Eigen::Index c = 0; c < m.cols(); ++c) values.append(c ? " " : "").append(number(m(r, c)));
    throw SolverError(path + ": not written: " + row_name + " " + std::to_string(r) + " has a non-finite value (" + values +
                      "); fairshape writes finite numbers only");
  }
}

void require_finite(const SparseMatrix& A, const std::string& path) {
  for (int k = 0; k < A.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(A, k); it; ++it)
      if (!std::isfinite(it.value()))
        throw SolverError(path + ": not written: entry (" + std::to_string(it.row()) + ", " + std::to_string(it.col()) +
                          ") is " + number(it.value()) + "; fairshape writes finite numbers only");
}

}  // namespace fairshape::io::internal
