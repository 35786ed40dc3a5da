// The TBB kernels the optimized iterative solvers share, on a row-major matrix and row-major
// blocks (the x, y, z of one unknown side by side, so a row touches one cache line per
// neighbour) of 1 to 3 columns. Every reduction is deterministic for a fixed thread count.
#pragma once

#include <utility>
#include <vector>

#include "fairshape/core/types.h"

namespace fairshape {

using RowBlock = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

//! Multicolour Gauss-Seidel / SOR: rows of one colour share no off-diagonal entry, so each
//! colour is one parallel loop; `forward` = false runs the colours in reverse (the adjoint
//! sweep, which makes a pre/post pair symmetric).
class MulticolorSmoother {
 public:
  void analyze(const RowSparseMatrix& A);
  void sweep(const RowSparseMatrix& A, RowBlock& x, const RowBlock& b, double omega, bool forward) const;
  const Eigen::VectorXd& diagonal() const { return diag_; }
  int colors() const { return static_cast<int>(classes_.size()); }

 private:
  static constexpr std::size_t kParallelRows = 512;
  Eigen::VectorXd diag_, inv_diag_;
  std::vector<std::vector<int>> classes_;
};

//! Block multicolour Gauss-Seidel / SOR on a system renumbered by a BlockOrdering: the colours
//! in turn, the blocks of one colour in parallel, each block's rows in order (backward: colours
//! and rows reversed, the adjoint sweep). Blocks of one colour share no entry, so the result
//! does not depend on the thread count.
class BlockSmoother {
 public:
  void analyze(const RowSparseMatrix& A_renumbered, std::vector<std::vector<std::pair<int, int>>> color_blocks);
  void sweep(const RowSparseMatrix& A, RowBlock& x, const RowBlock& b, double omega, bool forward) const;
  int colors() const { return static_cast<int>(color_blocks_.size()); }

 private:
  Eigen::VectorXd inv_diag_;
  std::vector<std::vector<std::pair<int, int>>> color_blocks_;
};

//! y = A x
void parallel_multiply(const RowSparseMatrix& A, const RowBlock& x, RowBlock& y);
//! r = b − A x
void parallel_residual(const RowSparseMatrix& A, const RowBlock& x, const RowBlock& b, RowBlock& r);
//! Σ_i a_ij c_ij for every column j.
Eigen::VectorXd parallel_column_dots(const RowBlock& a, const RowBlock& c);
//! y = Mᵀ x, in one pass over M's rows: chunks of rows scatter into their own copy of y,
//! summed in a fixed order (deterministic for a fixed thread count). For a tall M with few
//! columns, e.g. constraint rows propagated to a coarse level.
void parallel_transpose_multiply(const RowSparseMatrix& M, const RowBlock& x, RowBlock& y);
//! ‖M x − s c‖_F for column-major x and c (a deformation and its targets), without forming
//! either product: one parallel pass over M's rows, deterministic for a fixed thread count.
double parallel_residual_norm(const RowSparseMatrix& M, const Eigen::MatrixXd& x, double s, const Eigen::MatrixXd& c);
//! y += M x (M row-major: P for prolongation, Pᵀ stored row-major for restriction).
void parallel_multiply_add(const RowSparseMatrix& M, const RowBlock& x, RowBlock& y);
//! Pᵀ A P for symmetric A (rows of the result gathered in parallel, deterministic).
SparseMatrix parallel_galerkin_product(const SparseMatrix& A, const SparseMatrix& P);

}  // namespace fairshape
