// Minimum-norm least-squares solutions of A X = C (A sparse, m × k, any shape and rank;
// C with one column per coordinate). §4.3 of Boier-Martin et al. fixes the deformations of
// the constrained vertices this way before solving for the free ones: a point constraint
// propagated to a coarse level touches more vertices than it has equations, so the
// underdetermined case (minimum norm) is the common one.
#pragma once

#include <string>
#include <vector>

#include "core/backend.h"
#include "core/types.h"

namespace fairshape {

struct LeastSquaresResult {
  Eigen::MatrixXd X;  // k × columns of C
  int rank = 0;
  double residual = 0;  // ‖A X − C‖_F: nonzero when the constraints are inconsistent
};

//! Reference: Eigen SparseQR (of Aᵀ when m < k, for the minimum norm). Optimized: CHOLMOD on
//! A Aᵀ when m < k, SuiteSparseQR otherwise. Dependent rows (any size): A⁺C through a maximal
//! independent row set found by the same QR (see least_squares.cpp).
//! \throw InvalidInput for non-finite input or mismatched sizes.
LeastSquaresResult min_norm_least_squares(const SparseMatrix& A, const Eigen::MatrixXd& C, Backend backend);

//! A maximal set of linearly independent rows of A (ascending), from a rank-revealing QR of Aᵀ
//! (reference Eigen SparseQR, optimized SuiteSparseQR).
std::vector<int> independent_rows(const SparseMatrix& A, Backend backend);

//! The m × |rows| 0/1 matrix whose column k picks row rows[k]: pickᵀ A keeps those rows of A.
SparseMatrix row_picker(Eigen::Index m, const std::vector<int>& rows);

}  // namespace fairshape
