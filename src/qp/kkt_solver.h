// The Lagrange (KKT) solver of a QuadraticProgram: see kkt_solver.cpp.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "core/backend.h"
#include "qp/qp_solver.h"

namespace fairshape::qp {

class LuFactor;  // kkt_solver.cpp: UMFPACK or SparseLU

//! Rows R₁Pᵀ equivalent to A p = b, from a QR A P = Q R whose pivots below relative_tolerance ×
//! A's largest column norm count as zero, and b ↦ Q₁ᵀ b (= R₁₁⁻ᵀ (A P₁)ᵀ b). For consistent b
//! the same solutions; for inconsistent b the least-squares fit (§4.3's AᵀA p = Aᵀb, without
//! squaring A's condition number).
struct CompressedRows {
  SparseMatrix rows;
  std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)> targets;
};
CompressedRows compress_rows(const SparseMatrix& A, Backend backend, double relative_tolerance);
//! The rows a rank-revealing QR of Aᵀ keeps (same tolerance), and b ↦ those entries of b.
CompressedRows independent_rows_of(const SparseMatrix& A, Backend backend, double relative_tolerance);
//! Curve rows (eq. 7) along a curved path have singular values spread continuously down to
//! 1e-17 (the locking §4.2.2 warns of): directions weaker than this count as dependent.
inline constexpr double kRowDependenceTolerance = 1e-8;
//! Constraint blocks up to this many dense entries (rows × reached unknowns) are reduced densely.
inline constexpr double kDenseReductionEntries = 4e7;

//! [H sAᵀ; sA −δI]: the Lagrange matrix with scaled constraint rows (δ = 0: the exact system).
SparseMatrix lagrange_matrix(const SparseMatrix& H, const SparseMatrix& A, double scale, double regularization = 0);

class KktSolver final : public QpSolver {
 public:
  explicit KktSolver(Backend backend);
  ~KktSolver() override;
  void analyze(const QuadraticProgram& qp) override;
  QpReport solve(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b) override;
  //! Symbolic analyses of the main system so far: analyze() on a program with the same
  //! sparsity pattern (new weights, a new rest shape) factors numerically only.
  int symbolic_analyses() const;

 private:
  struct System;
  std::unique_ptr<System> build(CompressedRows rows, std::unique_ptr<LuFactor> recycled);
  QpReport solve_with(const System& sys, const Eigen::MatrixXd& f, const Eigen::MatrixXd& b) const;

  Backend backend_;
  SparseMatrix H_, A_;
  double scale_ = 1;
  std::unique_ptr<System> main_, least_squares_;
  bool reduced_ = false;  // main_ works on R₁Pᵀ rather than a subset of A's rows
};

}  // namespace fairshape::qp
