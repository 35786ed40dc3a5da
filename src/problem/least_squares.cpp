#include "problem/least_squares.h"

#include <Eigen/Dense>
#include <Eigen/SparseQR>
#include <Eigen/CholmodSupport>
#include <Eigen/SPQRSupport>

#include "core/error.h"

namespace fairshape {
namespace {

// Dense complete orthogonal decomposition: exact minimum norm for any rank, but O(m k min(m,k))
// time and m k memory, so only for small systems (rank-deficient fallbacks).
constexpr double kDenseLimit = 4e6;  // entries

LeastSquaresResult dense_cod(const SparseMatrix& A, const Eigen::MatrixXd& C) {
  if (double(A.rows()) * double(A.cols()) > kDenseLimit)
    throw SolverError("least squares: the constraints are dependent (rank-deficient) and the system (" +
                      std::to_string(A.rows()) + " x " + std::to_string(A.cols()) +
                      ") is too large for the dense fallback: remove redundant constraints");
  const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod{Eigen::MatrixXd(A)};
  LeastSquaresResult r;
  r.X = cod.solve(C);
  r.rank = static_cast<int>(cod.rank());
  return r;
}

// Reference: Eigen's SparseQR. m >= k: least squares through A P = Q R. m < k: minimum norm
// through the QR of Aᵀ: Aᵀ P = Q R gives A = P Rᵀ Qᵀ, so x = Q [R₁⁻ᵀ Pᵀ C; 0].
LeastSquaresResult sparse_qr(const SparseMatrix& A, const Eigen::MatrixXd& C) {
  LeastSquaresResult r;
  const bool wide = A.rows() < A.cols();
  SparseMatrix M = wide ? SparseMatrix(A.transpose()) : A;
  M.makeCompressed();
  Eigen::SparseQR<SparseMatrix, Eigen::COLAMDOrdering<int>> qr(M);
  if (qr.info() != Eigen::Success) throw SolverError("least squares: sparse QR failed on the constraint system");
  r.rank = static_cast<int>(qr.rank());
  if (r.rank < std::min(A.rows(), A.cols())) return dense_cod(A, C);
  if (!wide) {
    r.X = qr.solve(C);
    return r;
  }
  const Eigen::Index m = A.rows();
  const Eigen::MatrixXd PtC = qr.colsPermutation().transpose() * C;
  const SparseMatrix R = qr.matrixR().topLeftCorner(m, m);
  Eigen::MatrixXd y = Eigen::MatrixXd::Zero(A.cols(), C.cols());
  y.topRows(m) = SparseMatrix(R.transpose()).triangularView<Eigen::Lower>().solve(PtC);
  r.X = qr.matrixQ() * y;
  return r;
}

// Optimized: underdetermined (m < k, the usual case for propagated constraints) via CHOLMOD on
// the small m × m system A Aᵀ; otherwise SuiteSparseQR. Dependent rows: the dense fallback.
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
  if (qr.info() != Eigen::Success) throw SolverError("least squares: SuiteSparseQR failed on the constraint system");
  r.X = qr.solve(C);
  r.rank = static_cast<int>(qr.rank());
  if (r.rank < A.cols()) return dense_cod(A, C);  // SPQR's basic solution is not minimum norm
  return r;
}

}  // namespace

LeastSquaresResult min_norm_least_squares(const SparseMatrix& A, const Eigen::MatrixXd& C, Backend backend) {
  if (A.rows() != C.rows())
    throw InvalidInput("least squares: " + std::to_string(A.rows()) + " constraint rows but " +
                       std::to_string(C.rows()) + " targets");
  if (!C.allFinite()) throw InvalidInput("least squares: a constraint target is not finite");
  LeastSquaresResult r = backend == Backend::Reference ? sparse_qr(A, C) : sparse_least_squares(A, C);
  r.residual = (A * r.X - C).norm();
  return r;
}

}  // namespace fairshape
