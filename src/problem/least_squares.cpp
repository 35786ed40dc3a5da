#include "fairshape/problem/least_squares.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/CholmodSupport>
#include <Eigen/SPQRSupport>
#include <Eigen/SparseQR>

#include "fairshape/core/error.h"

namespace fairshape {

// One factored route to A⁺: solve(C) applies it to a block of targets.
struct MinNormLeastSquares::Factorization {
  virtual ~Factorization() = default;
  virtual Eigen::MatrixXd solve(const Eigen::MatrixXd& C) const = 0;
  int rank = 0;
};

namespace {

using ReferenceQR = Eigen::SparseQR<SparseMatrix, Eigen::COLAMDOrdering<int>>;
using OptimizedQR = Eigen::SPQR<SparseMatrix>;
using Factorization = MinNormLeastSquares::Factorization;

SparseMatrix compressed(SparseMatrix M) {
  M.makeCompressed();
  return M;
}

// Dependent rows (a fixed region propagated to a coarse level gives many more rows than the
// vertices they touch). With A_I a maximal independent set of A's rows (the first `rank`
// pivots of a QR of Aᵀ; both QRs move dependent columns last), every x = A_Iᵀ w lies in A's
// row space, and B = A A_Iᵀ has full column rank; w = argmin ‖B w − C‖ is unique, so x is
// the least-squares solution of least norm, A⁺C, and stays sparse whatever the size.
template <class QR>
std::vector<int> independent_rows_by(const SparseMatrix& A, double tolerance = kRowDependenceTolerance) {
  const SparseMatrix At = compressed(A.transpose());
  QR qr;
  qr.setPivotThreshold(tolerance * largest_column_norm(At));
  qr.compute(At);
  if (qr.info() != Eigen::Success) throw SolverError("least squares: QR of the constraint rows failed");
  const auto permutation = qr.colsPermutation();  // SPQR returns it by value: keep it alive
  const auto& perm = permutation.indices();
  std::vector<int> rows;
  for (Eigen::Index k = 0; k < qr.rank(); ++k) rows.push_back(static_cast<int>(perm[k]));
  std::sort(rows.begin(), rows.end());
  return rows;
}

template <class QR>
struct RankDeficient final : Factorization {
  SparseMatrix AIt;  // A_Iᵀ
  QR b_qr;           // of B = A A_Iᵀ
  explicit RankDeficient(const SparseMatrix& A) {
    const std::vector<int> rows = independent_rows_by<QR>(A);
    AIt = SparseMatrix(A.transpose()) * row_picker(A.rows(), rows);
    b_qr.compute(compressed(A * AIt));
    if (b_qr.info() != Eigen::Success) throw SolverError("least squares: QR of the reduced constraint system failed");
    rank = static_cast<int>(rows.size());
  }
  Eigen::MatrixXd solve(const Eigen::MatrixXd& C) const override { return AIt * Eigen::MatrixXd(b_qr.solve(C)); }
};

// Reference, m >= k and full rank: least squares through A P = Q R.
struct ReferenceTall final : Factorization {
  ReferenceQR qr;
  explicit ReferenceTall(const SparseMatrix& A) : qr(compressed(A)) { rank = static_cast<int>(qr.rank()); }
  Eigen::MatrixXd solve(const Eigen::MatrixXd& C) const override { return qr.solve(C); }
};

// Reference, m < k and full rank: minimum norm through the QR of Aᵀ: Aᵀ P = Q R gives
// A = P Rᵀ Qᵀ, so x = Q [R₁⁻ᵀ Pᵀ C; 0].
struct ReferenceWide final : Factorization {
  ReferenceQR qr;
  SparseMatrix Rt;  // R₁ᵀ, lower triangular
  explicit ReferenceWide(const SparseMatrix& A) : qr(compressed(A.transpose())) {
    rank = static_cast<int>(qr.rank());
    Rt = SparseMatrix(qr.matrixR().topLeftCorner(A.rows(), A.rows())).transpose();
  }
  Eigen::MatrixXd solve(const Eigen::MatrixXd& C) const override {
    Eigen::MatrixXd y = Eigen::MatrixXd::Zero(qr.rows(), C.cols());
    const Eigen::MatrixXd PtC = qr.colsPermutation().transpose() * C;
    y.topRows(Rt.rows()) = Rt.triangularView<Eigen::Lower>().solve(PtC);
    return qr.matrixQ() * y;
  }
};

// Optimized, m < k (the usual case for propagated constraints): CHOLMOD on the small m × m
// system A Aᵀ, x = Aᵀ (A Aᵀ)⁻¹ C.
struct OptimizedWide final : Factorization {
  SparseMatrix At;
  Eigen::CholmodSupernodalLLT<SparseMatrix> llt;
  explicit OptimizedWide(const SparseMatrix& A) : At(A.transpose()) {
    // Dependent rows make A Aᵀ singular: expected, detected by usable() and routed to the QR
    // (a CHOLMOD "not positive definite" warning on stderr would only alarm).
    llt.cholmod().print = 0;
    llt.compute(A * At);
  }
  // CHOLMOD may factor a numerically singular A Aᵀ (dependent rows): a probe solve decides.
  bool usable(const SparseMatrix& A) const {
    if (llt.info() != Eigen::Success) return false;
    std::mt19937 gen(7);
    std::uniform_real_distribution<double> d(-1, 1);
    Eigen::VectorXd probe(A.cols());
    for (auto& v : probe) v = d(gen);
    const Eigen::VectorXd c = A * probe, y = llt.solve(c);
    return llt.info() == Eigen::Success && y.allFinite() && (A * (At * y) - c).norm() <= 1e-8 * c.norm();
  }
  Eigen::MatrixXd solve(const Eigen::MatrixXd& C) const override { return At * Eigen::MatrixXd(llt.solve(C)); }
};

// Optimized, m >= k and full column rank: SuiteSparseQR (its basic solution of a
// rank-deficient A is not the minimum norm one: that goes through RankDeficient).
struct OptimizedTall final : Factorization {
  OptimizedQR qr;
  explicit OptimizedTall(const SparseMatrix& A) : qr(compressed(A)) {
    if (qr.info() != Eigen::Success) throw SolverError("least squares: SuiteSparseQR failed on the constraint system");
    rank = static_cast<int>(qr.rank());
  }
  Eigen::MatrixXd solve(const Eigen::MatrixXd& C) const override { return qr.solve(C); }
};

std::unique_ptr<Factorization> factor_reference(const SparseMatrix& A) {
  std::unique_ptr<Factorization> f;
  if (A.rows() < A.cols()) f = std::make_unique<ReferenceWide>(A);
  else f = std::make_unique<ReferenceTall>(A);
  if (f->rank < std::min(A.rows(), A.cols())) f = std::make_unique<RankDeficient<ReferenceQR>>(A);
  return f;
}

std::unique_ptr<Factorization> factor_optimized(const SparseMatrix& A) {
  if (A.rows() < A.cols()) {
    auto wide = std::make_unique<OptimizedWide>(A);
    if (wide->usable(A)) {
      wide->rank = static_cast<int>(A.rows());
      return wide;
    }
    return std::make_unique<RankDeficient<OptimizedQR>>(A);
  }
  auto tall = std::make_unique<OptimizedTall>(A);
  if (tall->rank < A.cols()) return std::make_unique<RankDeficient<OptimizedQR>>(A);
  return tall;
}

}  // namespace

MinNormLeastSquares::MinNormLeastSquares(const SparseMatrix& A, Backend backend) : A_(A) {
  require_backend(backend);
  for (int c = 0; c < A.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(A, c); it; ++it)
      if (!std::isfinite(it.value())) throw InvalidInput("least squares: a constraint coefficient is not finite");
  f_ = backend == Backend::Reference ? factor_reference(A) : factor_optimized(A);
}

MinNormLeastSquares::~MinNormLeastSquares() = default;
MinNormLeastSquares::MinNormLeastSquares(MinNormLeastSquares&&) noexcept = default;
MinNormLeastSquares& MinNormLeastSquares::operator=(MinNormLeastSquares&&) noexcept = default;

int MinNormLeastSquares::rank() const { return f_->rank; }

LeastSquaresResult MinNormLeastSquares::solve(const Eigen::MatrixXd& C) const {
  if (A_.rows() != C.rows())
    throw InvalidInput("least squares: " + std::to_string(A_.rows()) + " constraint rows but " +
                       std::to_string(C.rows()) + " targets");
  if (!C.allFinite()) throw InvalidInput("least squares: a constraint target is not finite");
  LeastSquaresResult r;
  r.X = f_->solve(C);
  r.rank = f_->rank;
  r.residual = (A_ * r.X - C).norm();
  return r;
}

std::vector<int> reached_columns(const SparseMatrix& A) {
  std::vector<int> reached;
  for (int c = 0; c < A.outerSize(); ++c)
    if (SparseMatrix::InnerIterator(A, c)) reached.push_back(c);
  return reached;
}

SparseMatrix row_picker(Eigen::Index m, const std::vector<int>& rows) {
  Triplets t;
  for (std::size_t k = 0; k < rows.size(); ++k) t.emplace_back(rows[k], static_cast<int>(k), 1.0);
  SparseMatrix pick(m, static_cast<Eigen::Index>(rows.size()));
  pick.setFromTriplets(t.begin(), t.end());
  return pick;
}

double largest_column_norm(const SparseMatrix& M) {
  double largest = 0;
  for (int c = 0; c < M.outerSize(); ++c) largest = std::max(largest, M.col(c).norm());
  return largest;
}

std::vector<int> independent_rows(const SparseMatrix& A, Backend backend, double tolerance) {
  return backend == Backend::Reference ? independent_rows_by<ReferenceQR>(A, tolerance) : independent_rows_by<OptimizedQR>(A, tolerance);
}

LeastSquaresResult min_norm_least_squares(const SparseMatrix& A, const Eigen::MatrixXd& C, Backend backend) {
  return MinNormLeastSquares(A, backend).solve(C);
}

}  // namespace fairshape
