#include "problem/least_squares.h"

#include <algorithm>

#include <Eigen/SparseQR>
#include <Eigen/CholmodSupport>
#include <Eigen/SPQRSupport>

#include "core/error.h"

namespace fairshape {
namespace {

// Dependent rows (a fixed region propagated to a coarse level gives many more rows than the
// vertices they touch). With A_I a maximal independent set of A's rows (the first `rank`
// pivots of a QR of Aᵀ; both QRs move dependent columns last), every x = A_Iᵀ w lies in A's
// row space, and B = A A_Iᵀ has full column rank; w = argmin ‖B w − C‖ is unique, so x is
// the least-squares solution of least norm, A⁺C, and stays sparse whatever the size.
template <class QR>
std::vector<int> independent_rows_by(const SparseMatrix& A) {
  SparseMatrix At = A.transpose();
  At.makeCompressed();
  QR qr(At);
  if (qr.info() != Eigen::Success) throw SolverError("least squares: QR of the constraint rows failed");
  const auto permutation = qr.colsPermutation();  // SPQR returns it by value: keep it alive
  const auto& perm = permutation.indices();
  std::vector<int> rows;
  for (Eigen::Index k = 0; k < qr.rank(); ++k) rows.push_back(static_cast<int>(perm[k]));
  std::sort(rows.begin(), rows.end());
  return rows;
}

template <class QR>
LeastSquaresResult rank_deficient(const SparseMatrix& A, const Eigen::MatrixXd& C) {
  const std::vector<int> rows = independent_rows_by<QR>(A);
  const SparseMatrix AIt = SparseMatrix(A.transpose()) * row_picker(A.rows(), rows);  // A_Iᵀ
  SparseMatrix B = A * AIt;
  B.makeCompressed();
  QR b_qr(B);
  if (b_qr.info() != Eigen::Success) throw SolverError("least squares: QR of the reduced constraint system failed");
  const Eigen::MatrixXd w = b_qr.solve(C);
  LeastSquaresResult r;
  r.X = AIt * w;
  r.rank = static_cast<int>(rows.size());
  return r;
}

using ReferenceQR = Eigen::SparseQR<SparseMatrix, Eigen::COLAMDOrdering<int>>;

// Reference: Eigen's SparseQR. m >= k: least squares through A P = Q R. m < k: minimum norm
// through the QR of Aᵀ: Aᵀ P = Q R gives A = P Rᵀ Qᵀ, so x = Q [R₁⁻ᵀ Pᵀ C; 0].
LeastSquaresResult sparse_qr(const SparseMatrix& A, const Eigen::MatrixXd& C) {
  LeastSquaresResult r;
  const bool wide = A.rows() < A.cols();
  SparseMatrix M = wide ? SparseMatrix(A.transpose()) : A;
  M.makeCompressed();
  ReferenceQR qr(M);
  if (qr.info() != Eigen::Success) throw SolverError("least squares: sparse QR failed on the constraint system");
  r.rank = static_cast<int>(qr.rank());
  if (r.rank < std::min(A.rows(), A.cols())) return rank_deficient<ReferenceQR>(A, C);
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
// the small m × m system A Aᵀ; otherwise SuiteSparseQR. Dependent rows: rank_deficient.
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
    return rank_deficient<Eigen::SPQR<SparseMatrix>>(A, C);
  }
  SparseMatrix Ac = A;
  Ac.makeCompressed();
  Eigen::SPQR<SparseMatrix> qr(Ac);
  if (qr.info() != Eigen::Success) throw SolverError("least squares: SuiteSparseQR failed on the constraint system");
  r.X = qr.solve(C);
  r.rank = static_cast<int>(qr.rank());
  if (r.rank < A.cols()) return rank_deficient<Eigen::SPQR<SparseMatrix>>(A, C);  // SPQR's basic solution is not minimum norm
  return r;
}

}  // namespace

SparseMatrix row_picker(Eigen::Index m, const std::vector<int>& rows) {
  Triplets t;
  for (std::size_t k = 0; k < rows.size(); ++k) t.emplace_back(rows[k], static_cast<int>(k), 1.0);
  SparseMatrix pick(m, static_cast<Eigen::Index>(rows.size()));
  pick.setFromTriplets(t.begin(), t.end());
  return pick;
}

std::vector<int> independent_rows(const SparseMatrix& A, Backend backend) {
  return backend == Backend::Reference ? independent_rows_by<ReferenceQR>(A)
                                       : independent_rows_by<Eigen::SPQR<SparseMatrix>>(A);
}

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
