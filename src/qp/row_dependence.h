// When constraint rows count as dependent, and what replaces them: the one policy every
// constrained solver of fairshape follows (the Lagrange system, the range-space Schur
// complement, the surface editor's constraint modes).
//
// Dependent rows are common, not an accident: a fixed region propagated to a coarser level
// gives more rows than the vertices they reach (330k rows over 1k vertices on the cow), and
// curve rows (Welch & Witkin eq. 7) along a curved path have singular values spread
// continuously down to 1e-17 (the locking §4.2.2 warns of). A direction weaker than
// kRowDependenceTolerance × the strongest counts as dependent, in every solver.
#pragma once

#include <functional>

#include "fairshape/core/backend.h"
#include "fairshape/core/types.h"

namespace fairshape::qp {

//! Relative size (to the strongest) below which a direction of the constraint rows is dropped.
inline constexpr double kRowDependenceTolerance = 1e-8;
//! Constraint blocks whose dense QR costs up to this many flops (rows × reached unknowns ×
//! the smaller of the two) are reduced densely (column-pivoted Householder, rank-revealing in
//! practice: curve rows); larger ones by sparse QR (a fixed region propagated to a coarse
//! level: 30k rows over 800 vertices would take 20 s densely, every drag; 1e8 flops take
//! about 50 ms).
inline constexpr double kDenseReductionFlops = 1e8;

//! Rows equivalent to A p = b (every solution of these solves A p = b when b is consistent),
//! and the map b ↦ their targets.
struct CompressedRows {
  SparseMatrix rows;
  std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)> targets;
  //! True for an orthogonal reduction (R₁Pᵀ): for inconsistent b its solutions fit A p = b in
  //! the least-squares sense. False for a subset of A's own rows.
  bool orthogonal = false;
};

//! Rows R₁Pᵀ from a QR A P = Q R whose pivots below `tolerance` × the largest count as zero,
//! and b ↦ Q₁ᵀ b (= R₁₁⁻ᵀ (A P₁)ᵀ b). For consistent b the same solutions; for inconsistent b
//! the least-squares fit (§4.3's AᵀA p = Aᵀb, without squaring A's condition number).
CompressedRows compress_rows(const SparseMatrix& A, Backend backend, double tolerance = kRowDependenceTolerance);
//! The rows a rank-revealing QR of Aᵀ keeps (same tolerance), and b ↦ those entries of b.
CompressedRows independent_rows_of(const SparseMatrix& A, Backend backend, double tolerance = kRowDependenceTolerance);
//! The first choice of every solver: A's own independent rows, unless A has more rows than the
//! unknowns it reaches — they cannot be independent, and the orthogonal reduction is both
//! smaller and better conditioned than a subset.
CompressedRows without_dependent_rows(const SparseMatrix& A, Backend backend, double tolerance = kRowDependenceTolerance);

}  // namespace fairshape::qp
