#include "solver/parallel_kernels.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/partitioner.h>

#include "core/error.h"
#include "core/parallel_row_assembly.h"
#include "solver/graph_coloring.h"

namespace fairshape {

void MulticolorSmoother::analyze(const RowSparseMatrix& A) {
  classes_ = color_rows(A);
  diag_ = A.diagonal();
}

namespace {

// The kernels keep a row's partial sums in registers: one per coordinate, at most x, y, z.
constexpr Eigen::Index kMaxColumns = 3;
void check_columns(const RowBlock& x) { FAIRSHAPE_ASSERT(x.cols() <= kMaxColumns, "row kernels take at most 3 columns"); }

// s = Σ_j a_ij x_j over row i (without the diagonal term when `skip_diagonal`).
inline void row_product(const RowSparseMatrix& A, Eigen::Index i, const RowBlock& x, bool skip_diagonal,
                        double (&s)[kMaxColumns]) {
  s[0] = s[1] = s[2] = 0;
  for (RowSparseMatrix::InnerIterator it(A, i); it; ++it)
    if (!skip_diagonal || it.col() != i)
      for (Eigen::Index c = 0; c < x.cols(); ++c) s[c] += it.value() * x(it.col(), c);
}

// x_i ← (1 − ω) x_i + ω (b_i − Σ_{j≠i} a_ij x_j) / a_ii
inline void relax_row(const RowSparseMatrix& A, const Eigen::VectorXd& diag, int i, RowBlock& x, const RowBlock& b,
                      double omega) {
  double sigma[kMaxColumns];
  row_product(A, i, x, true, sigma);
  for (Eigen::Index c = 0; c < x.cols(); ++c) x(i, c) = (1 - omega) * x(i, c) + omega * (b(i, c) - sigma[c]) / diag[i];
}

}  // namespace

void MulticolorSmoother::sweep(const RowSparseMatrix& A, RowBlock& x, const RowBlock& b, double omega,
                               bool forward) const {
  check_columns(x);
  const int n_classes = colors();
  for (int k = 0; k < n_classes; ++k) {
    const std::vector<int>& rows = classes_[forward ? k : n_classes - 1 - k];
    // A colour of a small (coarse) level is not worth a parallel loop's synchronization.
    if (rows.size() < kParallelRows) {
      for (int i : rows) relax_row(A, diag_, i, x, b, omega);
      continue;
    }
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, rows.size(), 512),
        [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t q = r.begin(); q != r.end(); ++q) relax_row(A, diag_, rows[q], x, b, omega);
        },
        tbb::static_partitioner());
  }
}

void BlockSmoother::analyze(const RowSparseMatrix& A, std::vector<std::vector<std::pair<int, int>>> color_blocks) {
  diag_ = A.diagonal();
  color_blocks_ = std::move(color_blocks);
}

void BlockSmoother::sweep(const RowSparseMatrix& A, RowBlock& x, const RowBlock& b, double omega, bool forward) const {
  check_columns(x);
  const int n_colors = colors();
  for (int k = 0; k < n_colors; ++k) {
    const auto& blocks = color_blocks_[static_cast<std::size_t>(forward ? k : n_colors - 1 - k)];
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, blocks.size(), 1),
        [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t q = r.begin(); q != r.end(); ++q) {
            const auto [begin, end] = blocks[q];
            if (forward)
              for (int i = begin; i < end; ++i) relax_row(A, diag_, i, x, b, omega);
            else
              for (int i = end - 1; i >= begin; --i) relax_row(A, diag_, i, x, b, omega);
          }
        },
        tbb::static_partitioner());
  }
}

namespace {

template <class RowOp>
void for_rows(Eigen::Index n, const RowOp& op) {
  tbb::parallel_for(
      tbb::blocked_range<Eigen::Index>(0, n, 1024),
      [&](const tbb::blocked_range<Eigen::Index>& r) {
        for (Eigen::Index i = r.begin(); i != r.end(); ++i) op(i);
      },
      tbb::static_partitioner());
}

}  // namespace

void parallel_multiply(const RowSparseMatrix& A, const RowBlock& x, RowBlock& y) {
  check_columns(x);
  y.resize(A.rows(), x.cols());
  for_rows(A.rows(), [&](Eigen::Index i) {
    double s[kMaxColumns];
    row_product(A, i, x, false, s);
    for (Eigen::Index c = 0; c < x.cols(); ++c) y(i, c) = s[c];
  });
}

void parallel_residual(const RowSparseMatrix& A, const RowBlock& x, const RowBlock& b, RowBlock& r) {
  check_columns(x);
  r.resize(A.rows(), x.cols());
  for_rows(A.rows(), [&](Eigen::Index i) {
    double s[kMaxColumns];
    row_product(A, i, x, false, s);
    for (Eigen::Index c = 0; c < x.cols(); ++c) r(i, c) = b(i, c) - s[c];
  });
}

void parallel_multiply_add(const RowSparseMatrix& M, const RowBlock& x, RowBlock& y) {
  for_rows(M.rows(), [&](Eigen::Index i) {
    for (RowSparseMatrix::InnerIterator it(M, i); it; ++it)
      for (Eigen::Index c = 0; c < x.cols(); ++c) y(i, c) += it.value() * x(it.col(), c);
  });
}

Eigen::VectorXd parallel_column_dots(const RowBlock& a, const RowBlock& c) {
  const Eigen::Index cols = a.cols();
  return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<Eigen::Index>(0, a.rows(), 4096), Eigen::VectorXd(Eigen::VectorXd::Zero(cols)),
      [&](const tbb::blocked_range<Eigen::Index>& r, Eigen::VectorXd acc) {
        for (Eigen::Index i = r.begin(); i != r.end(); ++i)
          for (Eigen::Index j = 0; j < cols; ++j) acc[j] += a(i, j) * c(i, j);
        return acc;
      },
      [](const Eigen::VectorXd& x, const Eigen::VectorXd& y) { return Eigen::VectorXd(x + y); });
}

SparseMatrix parallel_galerkin_product(const SparseMatrix& A_in, const SparseMatrix& P_in) {
  // Row I of PᵀAP = Σ_{i ∈ column I of P} P_iI Σ_j A_ij P_j.
  const RowSparseMatrix A(A_in), P(P_in), PT(P_in.transpose());
  return assemble_symmetric_by_rows(static_cast<int>(P.cols()), 512, [&](int I, const auto& add, bool values) {
    for (RowSparseMatrix::InnerIterator pi(PT, I); pi; ++pi)
      for (RowSparseMatrix::InnerIterator a(A, pi.col()); a; ++a)
        for (RowSparseMatrix::InnerIterator pj(P, a.col()); pj; ++pj)
          add(static_cast<int>(pj.col()), values ? pi.value() * a.value() * pj.value() : 0.0);
  });
}

}  // namespace fairshape
