#include "fairshape/qp/row_dependence.h"

#include <Eigen/QR>
#include <Eigen/SPQRSupport>
#include <Eigen/SparseQR>

#include <algorithm>
#include <memory>

#include "fairshape/core/error.h"
#include "fairshape/problem/least_squares.h"
#include "fairshape/solver/parallel_kernels.h"

namespace fairshape::qp {

static_assert(kRowDependenceTolerance == fairshape::kRowDependenceTolerance, "one rank policy");

namespace {

bool dense_enough(const SparseMatrix& A, const std::vector<int>& reached) {
  const double m = static_cast<double>(A.rows()), k = static_cast<double>(reached.size());
  return m * k * std::min(m, k) <= kDenseReductionFlops;
}

// R₁Pᵀ on the full unknowns: the leading rows S of R, whose column c is unknown column_of(c).
SparseMatrix rows_from(const SparseMatrix& S, Eigen::Index cols, const std::function<int(Eigen::Index)>& column_of) {
  Triplets t;
  for (int c = 0; c < S.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(S, c); it; ++it) t.emplace_back(static_cast<int>(it.row()), column_of(c), it.value());
  SparseMatrix out(S.rows(), cols);
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

// Q₁ᵀ b = R₁₁⁻ᵀ (A P₁)ᵀ b: one product with the kept columns of A and one sparse triangular
// solve per right-hand side, instead of applying Q's Householder vectors. The optimized back
// end makes the product one parallel pass over A's rows (hundreds of thousands of them, every
// step of a drag).
std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)> compressed_targets(const SparseMatrix& R11t, const SparseMatrix& AP1,
                                                                          Backend backend) {
#if FAIRSHAPE_WITH_TBB
  if (backend == Backend::Optimized) {
    const RowSparseMatrix AP1_rows(AP1);
    return [R11t, AP1_rows](const Eigen::MatrixXd& b) {
      RowBlock y;
      parallel_transpose_multiply(AP1_rows, RowBlock(b), y);
      return Eigen::MatrixXd(R11t.triangularView<Eigen::Lower>().solve(Eigen::MatrixXd(y)));
    };
  }
#endif
  require_backend(backend);
  const SparseMatrix AP1t = AP1.transpose();
  return [R11t, AP1t](const Eigen::MatrixXd& b) {
    return Eigen::MatrixXd(R11t.triangularView<Eigen::Lower>().solve(Eigen::MatrixXd(AP1t * b)));
  };
}

template <class QR>
CompressedRows sparse_compression(const SparseMatrix& A, const std::vector<int>& reached, Backend backend, double tolerance) {
  SparseMatrix on_reached = A * row_picker(A.cols(), reached);
  on_reached.makeCompressed();
  QR qr;
  qr.setPivotThreshold(tolerance * largest_column_norm(on_reached));
  qr.compute(on_reached);
  if (qr.info() != Eigen::Success) throw SolverError("constraint rows: sparse QR failed");
  const Eigen::Index rank = qr.rank();
  const auto permutation = qr.colsPermutation();  // SPQR returns it by value: keep it alive
  const Eigen::VectorXi perm = permutation.indices().template cast<int>();
  const SparseMatrix R = SparseMatrix(qr.matrixR()).topRows(rank);
  CompressedRows out;
  out.orthogonal = true;
  out.rows = rows_from(R, A.cols(), [&](Eigen::Index c) { return reached[perm[c]]; });
  std::vector<int> leading(static_cast<std::size_t>(rank));
  for (Eigen::Index k = 0; k < rank; ++k) leading[static_cast<std::size_t>(k)] = perm[k];
  const SparseMatrix R11t = SparseMatrix(R.leftCols(rank)).transpose();
  out.targets = compressed_targets(R11t, on_reached * row_picker(on_reached.cols(), leading), backend);
  return out;
}

}  // namespace

CompressedRows compress_rows(const SparseMatrix& A, Backend backend, double tolerance) {
  const std::vector<int> reached = reached_columns(A);
  if (!dense_enough(A, reached)) {
    if (backend == Backend::Reference)
      return sparse_compression<Eigen::SparseQR<SparseMatrix, Eigen::COLAMDOrdering<int>>>(A, reached, backend, tolerance);
    return sparse_compression<Eigen::SPQR<SparseMatrix>>(A, reached, backend, tolerance);
  }
  // Column-pivoted Householder QR of A on the unknowns it reaches: rank-revealing in practice
  // (SPQR's pivot threshold is a heuristic that keeps nearly dependent curve rows).
  auto qr = std::make_shared<Eigen::ColPivHouseholderQR<Eigen::MatrixXd>>();
  qr->setThreshold(tolerance);
  qr->compute(Eigen::MatrixXd(A * row_picker(A.cols(), reached)));
  const Eigen::Index k = qr->rank();
  const Eigen::MatrixXd R = qr->matrixR().topRows(k).triangularView<Eigen::Upper>();
  CompressedRows out;
  out.orthogonal = true;
  out.rows = rows_from(R.sparseView(), A.cols(), [&](Eigen::Index c) { return reached[qr->colsPermutation().indices()[c]]; });
  out.targets = [qr, k](const Eigen::MatrixXd& b) { return Eigen::MatrixXd((qr->householderQ().transpose() * b).topRows(k)); };
  return out;
}

CompressedRows independent_rows_of(const SparseMatrix& A, Backend backend, double tolerance) {
  const std::vector<int> reached = reached_columns(A);
  std::vector<int> keep;
  if (dense_enough(A, reached)) {
    // Column pivoting on Aᵀ picks rows in order of independence: rank-revealing in practice.
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr;
    qr.setThreshold(tolerance);
    qr.compute(Eigen::MatrixXd(SparseMatrix(A * row_picker(A.cols(), reached)).transpose()));
    for (Eigen::Index k = 0; k < qr.rank(); ++k) keep.push_back(qr.colsPermutation().indices()[k]);
    std::sort(keep.begin(), keep.end());
  } else {
    keep = independent_rows(A, backend, tolerance);
  }
  const SparseMatrix pick_t = SparseMatrix(row_picker(A.rows(), keep).transpose());
  return {pick_t * A, [pick_t](const Eigen::MatrixXd& b) { return Eigen::MatrixXd(pick_t * b); }, false};
}

CompressedRows without_dependent_rows(const SparseMatrix& A, Backend backend, double tolerance) {
  if (A.rows() == 0) return {SparseMatrix(0, A.cols()), [](const Eigen::MatrixXd& b) { return b; }, false};
  if (A.rows() > static_cast<Eigen::Index>(reached_columns(A).size())) return compress_rows(A, backend, tolerance);
  return independent_rows_of(A, backend, tolerance);
}

}  // namespace fairshape::qp
