// One lexicographic SOR sweep, straight from the textbook (ω = 1: Gauss-Seidel):
//   x_i ← (1 − ω) x_i + ω (b_i − Σ_{j≠i} a_ij x_j) / a_ii,   i = 0, 1, …, n − 1
// (or n − 1, …, 0 for the backward sweep). Shared by the reference `gauss_seidel`/`sor`
// solvers and the reference multigrid smoother.
#pragma once

#include "fairshape/core/types.h"

namespace fairshape::reference {

inline void lexicographic_sweep(const RowSparseMatrix& A, const Eigen::VectorXd& diag, Eigen::MatrixXd& x,
                                const Eigen::MatrixXd& b, double omega, bool forward = true) {
  const Eigen::Index n = A.rows();
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Index i = forward ? k : n - 1 - k;
    Eigen::RowVectorXd sigma = Eigen::RowVectorXd::Zero(x.cols());
    for (RowSparseMatrix::InnerIterator e(A, i); e; ++e)
      if (e.col() != i) sigma += e.value() * x.row(e.col());
    x.row(i) = (1 - omega) * x.row(i) + omega * (b.row(i) - sigma) / diag[i];
  }
}

}  // namespace fairshape::reference
