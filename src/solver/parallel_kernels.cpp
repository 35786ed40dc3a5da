#include "fairshape/solver/parallel_kernels.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/partitioner.h>

#include <cmath>
#include <functional>

#include "fairshape/core/error.h"
#include "fairshape/core/parallel_row_assembly.h"
#include "fairshape/solver/graph_coloring.h"
#include "fairshape/solver/row_kernels.h"
#include "fairshape/solver/symmetric_rows.h"

namespace fairshape {

namespace {

// x_i ← x_i + ω (b_i − Σ_j a_ij x_j) / a_ii, i.e. (1 − ω) x_i + ω (b_i − Σ_{j≠i} a_ij x_j) / a_ii.
template <int C>
inline void relax_row(const CsrView& A, const double* inv_diag, Eigen::Index i, double* x, const double* b,
                      double omega) {
  double s[C];
  row_sum<C>(A, i, x, s);
  for (int c = 0; c < C; ++c) x[i * C + c] += omega * (b[i * C + c] - s[c]) * inv_diag[i];
}

Eigen::VectorXd inverse_diagonal(const RowSparseMatrix& A) { return A.diagonal().cwiseInverse(); }

}  // namespace

void MulticolorSmoother::analyze(const RowSparseMatrix& A) {
  classes_ = color_rows(A);
  diag_ = A.diagonal();
  inv_diag_ = inverse_diagonal(A);
}

void MulticolorSmoother::sweep(const RowSparseMatrix& A, RowBlock& x, const RowBlock& b, double omega,
                               bool forward) const {
  const CsrView csr(A);
  const int n_classes = colors();
  with_columns(x.cols(), [&](auto C) {
    for (int k = 0; k < n_classes; ++k) {
      const std::vector<int>& rows = classes_[forward ? k : n_classes - 1 - k];
      const auto relax = [&](int i) { relax_row<C>(csr, inv_diag_.data(), i, x.data(), b.data(), omega); };
      // A colour of a small (coarse) level is not worth a parallel loop's synchronization.
      if (rows.size() < kParallelRows) {
        for (int i : rows) relax(i);
        continue;
      }
      tbb::parallel_for(
          tbb::blocked_range<std::size_t>(0, rows.size(), 512),
          [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t q = r.begin(); q != r.end(); ++q) relax(rows[q]);
          },
          tbb::static_partitioner());
    }
  });
}

void BlockSmoother::analyze(const RowSparseMatrix& A, std::vector<std::vector<std::pair<int, int>>> color_blocks) {
  inv_diag_ = inverse_diagonal(A);
  color_blocks_ = std::move(color_blocks);
}

void BlockSmoother::sweep(const RowSparseMatrix& A, RowBlock& x, const RowBlock& b, double omega, bool forward) const {
  const CsrView csr(A);
  const int n_colors = colors();
  with_columns(x.cols(), [&](auto C) {
    for (int k = 0; k < n_colors; ++k) {
      const auto& blocks = color_blocks_[static_cast<std::size_t>(forward ? k : n_colors - 1 - k)];
      tbb::parallel_for(
          tbb::blocked_range<std::size_t>(0, blocks.size(), 1),
          [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t q = r.begin(); q != r.end(); ++q) {
              const auto [begin, end] = blocks[q];
              const auto relax = [&](int i) { relax_row<C>(csr, inv_diag_.data(), i, x.data(), b.data(), omega); };
              if (forward)
                for (int i = begin; i < end; ++i) relax(i);
              else
                for (int i = end - 1; i >= begin; --i) relax(i);
            }
          },
          tbb::static_partitioner());
    }
  });
}

namespace {

// store(k, s) for every entry k = i·C + c of the row-major result, s = Σ_j a_ij x_jc; rows in
// parallel. The products, residuals and transfers differ only in what they store.
template <class Store>
void for_each_row_sum(const RowSparseMatrix& A, const RowBlock& x, const Store& store) {
  const CsrView csr(A);
  with_columns(x.cols(), [&](auto C) {
    tbb::parallel_for(
        tbb::blocked_range<Eigen::Index>(0, A.rows(), 1024),
        [&](const tbb::blocked_range<Eigen::Index>& r) {
          for (Eigen::Index i = r.begin(); i != r.end(); ++i) {
            double s[C];
            row_sum<C>(csr, i, x.data(), s);
            for (int c = 0; c < C; ++c) store(i * C + c, s[c]);
          }
        },
        tbb::static_partitioner());
  });
}

}  // namespace

void parallel_multiply(const RowSparseMatrix& A, const RowBlock& x, RowBlock& y) {
  y.resize(A.rows(), x.cols());
  for_each_row_sum(A, x, [&](Eigen::Index k, double s) { y.data()[k] = s; });
}

void parallel_residual(const RowSparseMatrix& A, const RowBlock& x, const RowBlock& b, RowBlock& r) {
  r.resize(A.rows(), x.cols());
  for_each_row_sum(A, x, [&](Eigen::Index k, double s) { r.data()[k] = b.data()[k] - s; });
}

void parallel_multiply_add(const RowSparseMatrix& M, const RowBlock& x, RowBlock& y) {
  for_each_row_sum(M, x, [&](Eigen::Index k, double s) { y.data()[k] += s; });
}

void parallel_transpose_multiply(const RowSparseMatrix& M, const RowBlock& x, RowBlock& y) {
  const CsrView csr(M);
  const Eigen::Index cols = x.cols();
  y = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<Eigen::Index>(0, M.rows(), 16384), RowBlock(RowBlock::Zero(M.cols(), cols)),
      [&](const tbb::blocked_range<Eigen::Index>& r, RowBlock acc) {
        for (Eigen::Index i = r.begin(); i != r.end(); ++i)
          for (int k = csr.outer[i]; k < csr.outer[i + 1]; ++k)
            for (Eigen::Index c = 0; c < cols; ++c) acc(csr.inner[k], c) += csr.value[k] * x(i, c);
        return acc;
      },
      [](const RowBlock& a, const RowBlock& b) { return RowBlock(a + b); });
}

double parallel_residual_norm(const RowSparseMatrix& M, const Eigen::MatrixXd& x, double s, const Eigen::MatrixXd& c) {
  FAIRSHAPE_ASSERT(x.cols() == c.cols() && c.rows() == M.rows() && x.rows() == M.cols(), "residual norm: sizes differ");
  const CsrView csr(M);
  const double squares = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<Eigen::Index>(0, M.rows(), 16384), 0.0,
      [&](const tbb::blocked_range<Eigen::Index>& r, double acc) {
        for (Eigen::Index i = r.begin(); i != r.end(); ++i)
          for (Eigen::Index col = 0; col < x.cols(); ++col) {
            double Mx = 0;
            for (int k = csr.outer[i]; k < csr.outer[i + 1]; ++k) Mx += csr.value[k] * x(csr.inner[k], col);
            const double ri = Mx - s * c(i, col);
            acc += ri * ri;
          }
        return acc;
      },
      std::plus<double>());
  return std::sqrt(squares);
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
  // Row I of PᵀAP = Σ_{i ∈ column I of P} P_iI Σ_j A_ij P_j. A is symmetric: its columns are
  // read as its rows (no row-major copy of the largest operand).
  const auto A = rows_of_symmetric(A_in);
  const RowSparseMatrix P(P_in), PT(P_in.transpose());
  return assemble_symmetric_by_rows(static_cast<int>(P.cols()), 512, [&](int I, const auto& add, bool values) {
    for (RowSparseMatrix::InnerIterator pi(PT, I); pi; ++pi)
      for (SymmetricRows::InnerIterator a(A, pi.col()); a; ++a)
        for (RowSparseMatrix::InnerIterator pj(P, a.col()); pj; ++pj)
          add(static_cast<int>(pj.col()), values ? pi.value() * a.value() * pj.value() : 0.0);
  });
}

}  // namespace fairshape
