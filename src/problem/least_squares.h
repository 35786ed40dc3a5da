// Minimum-norm least-squares solutions of A X = C (A sparse, m × k, any shape and rank;
// C with one column per coordinate). §4.3 of Boier-Martin et al. fixes the deformations of
// the constrained vertices this way before solving for the free ones: a point constraint
// propagated to a coarse level touches more vertices than it has equations, so the
// underdetermined case (minimum norm) is the common one.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "fairshape/core/backend.h"
#include "fairshape/core/types.h"

namespace fairshape {

struct LeastSquaresResult {
  Eigen::MatrixXd X;  // k × columns of C
  int rank = 0;
  double residual = 0;  // ‖A X − C‖_F: nonzero when the constraints are inconsistent
};

//! A⁺ of one constraint matrix, factored once and applied to many targets: a drag moves the
//! targets of an unchanged constraint set, so only this solve is paid per step.
class MinNormLeastSquares {
 public:
  //! \throw InvalidInput for non-finite entries; SolverError when a factorization fails.
  MinNormLeastSquares(const SparseMatrix& A, Backend backend);
  ~MinNormLeastSquares();
  MinNormLeastSquares(MinNormLeastSquares&&) noexcept;
  MinNormLeastSquares& operator=(MinNormLeastSquares&&) noexcept;
  //! A⁺C. \throw InvalidInput when C's rows are not A's or C is not finite.
  LeastSquaresResult solve(const Eigen::MatrixXd& C) const;
  int rank() const;

  struct Factorization;  // least_squares.cpp: one per route (wide, tall, rank-deficient)

 private:
  SparseMatrix A_;
  std::unique_ptr<Factorization> f_;
};

//! Reference: Eigen SparseQR (of Aᵀ when m < k, for the minimum norm). Optimized: CHOLMOD on
//! A Aᵀ when m < k, SuiteSparseQR otherwise. Dependent rows (any size): A⁺C through a maximal
//! independent row set found by the same QR (see least_squares.cpp).
//! \throw InvalidInput for non-finite input or mismatched sizes.
LeastSquaresResult min_norm_least_squares(const SparseMatrix& A, const Eigen::MatrixXd& C, Backend backend);

//! Relative size (to the strongest) below which a direction of constraint rows counts as
//! dependent: the one rank policy of every constrained solve (see qp/row_dependence.h).
inline constexpr double kRowDependenceTolerance = 1e-8;

//! A maximal set of linearly independent rows of A (ascending), from a rank-revealing QR of Aᵀ
//! (reference Eigen SparseQR, optimized SuiteSparseQR) whose pivots below
//! `tolerance` × the largest row norm count as zero.
std::vector<int> independent_rows(const SparseMatrix& A, Backend backend, double tolerance = kRowDependenceTolerance);

//! The largest Euclidean norm of a column of M (0 for an empty M): the scale a QR's pivot
//! threshold is relative to.
double largest_column_norm(const SparseMatrix& M);

//! The columns of A with at least one entry (ascending): the unknowns its rows reach.
std::vector<int> reached_columns(const SparseMatrix& A);

//! The m × |rows| 0/1 matrix whose column k picks row rows[k]: pickᵀ A keeps those rows of A.
SparseMatrix row_picker(Eigen::Index m, const std::vector<int>& rows);

}  // namespace fairshape
