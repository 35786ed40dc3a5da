#include "problem/least_squares.h"

#include <Eigen/Dense>
#include <Eigen/CholmodSupport>
#include <Eigen/SPQRSupport>

#include "core/error.h"

namespace fairshape {
namespace {

LeastSquaresResult dense_cod(const SparseMatrix& A, const Eigen::MatrixXd& C) {
  const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod{Eigen::MatrixXd(A)};
  LeastSquaresResult r;
  r.X = cod.solve(C);
  r.rank = static_cast<int>(cod.rank());
  return r;
}

// Sparse path. Underdetermined (m < k, the usual case for propagated constraints): the
// minimum-norm solution Aᵀ (A Aᵀ)⁻¹ C through CHOLMOD on the small m × m system. Otherwise
// SuiteSparseQR least squares. Dependent rows make A Aᵀ singular: fall back to the dense COD.
LeastSquaresResult sparse_least_squares(const SparseMatrix& A, const Eigen::MatrixXd& C) {
  LeastSquaresResult r;
  if (A.rows() < A.cols()) {
    const SparseMatrix AAt = A * SparseMatrix(A.transpose());
    Eigen::CholmodSupernodalLLT<SparseMatrix> llt(AAt);
    if (llt.info() == Eigen::Success) {
      const Eigen::MatrixXd Y = llt.solve(C);
      if (llt.info() == Eigen::Success && Y.allFinite()) {
        r.X = SparseMatrix(A.transpose()) * Y;
        r.rank = static_cast<int>(A.rows());
        return r;
      }
    }
    return dense_cod(A, C);
  }
  SparseMatrix Ac = A;
  Ac.makeCompressed();
  Eigen::SPQR<SparseMatrix> qr(Ac);
  if (qr.info() != Eigen::Success) throw SolverError("SuiteSparseQR failed on the constraint system");
  r.X = qr.solve(C);
  r.rank = static_cast<int>(qr.rank());
  if (r.rank < A.cols()) return dense_cod(A, C);  // rank-deficient: SPQR's basic solution is not minimum norm
  return r;
}

}  // namespace

LeastSquaresResult min_norm_least_squares(const SparseMatrix& A, const Eigen::MatrixXd& C, Backend backend) {
  if (A.rows() != C.rows())
    throw InvalidInput("least squares: " + std::to_string(A.rows()) + " constraint rows but " +
                       std::to_string(C.rows()) + " targets");
  if (!C.allFinite()) throw InvalidInput("least squares: a constraint target is not finite");
  LeastSquaresResult r = backend == Backend::Reference ? dense_cod(A, C) : sparse_least_squares(A, C);
  r.residual = (A * r.X - C).norm();
  return r;
}

}  // namespace fairshape
