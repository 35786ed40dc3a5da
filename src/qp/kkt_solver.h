// The Lagrange (KKT) solver of a QuadraticProgram: see kkt_solver.cpp.
#pragma once

#include <memory>
#include <vector>

#include "fairshape/core/backend.h"
#include "fairshape/qp/qp_solver.h"
#include "fairshape/qp/constraint_policy.h"
#include "fairshape/qp/row_dependence.h"

namespace fairshape::qp {

class LuFactor;  // kkt_solver.cpp: UMFPACK or SparseLU
class PinnedReduction;
class RangeSpaceSolver;

//! [H sAᵀ; sA −δI]: the Lagrange matrix with scaled constraint rows (δ = 0: the exact system).
SparseMatrix lagrange_matrix(const SparseMatrix& H, const SparseMatrix& A, double scale, double regularization = 0);

class KktSolver final : public QpSolver {
 public:
  //! reuse: keep the factored system across analyze() calls with the same H and A.
  explicit KktSolver(Backend backend, ConstraintPolicy policy = {}, bool reuse = true);
  ~KktSolver() override;
  void analyze(const QuadraticProgram& qp) override;
  QpReport solve(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b) override;
  //! Symbolic analyses of the main system so far: analyze() on a program with the same
  //! sparsity pattern (new weights, a new rest shape) factors numerically only.
  int symbolic_analyses() const;
  //! Numeric factorizations so far, and whether the last analyze() kept the factored system:
  //! a program with the same H and A as the last one (a drag step: only f and b change) is
  //! not factored again (papers/welch-witkin/README.md, "A drag step and its checks").
  int factorizations() const { return factorizations_; }
  bool reused_factorization() const { return reused_; }

 private:
  struct System;
  std::unique_ptr<System> build(CompressedRows rows, std::unique_ptr<LuFactor> recycled);
  QpReport solve_with(const System& sys, const Eigen::MatrixXd& f, const Eigen::MatrixXd& b) const;
  void prepare_pinned_fallback();
  QpReport solve_pinned(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b);

  Backend backend_;
  ConstraintPolicy policy_;
  SparseMatrix H_, A_;  // A_: the unit-norm rows of A_original_
  SparseMatrix A_original_;
  RowScaling scaling_;
  ConstraintConditioning conditioning_;
  double scale_ = 1;
  std::unique_ptr<System> main_, least_squares_;
  bool reduced_ = false;  // main_ works on R₁Pᵀ rather than a subset of A's rows
  // When main_ stays singular: the unknowns pinned by rows of their own eliminated, the rest by
  // the range-space method (kkt_solver.cpp).
  std::unique_ptr<PinnedReduction> pinned_;
  std::unique_ptr<RangeSpaceSolver> pinned_solver_;
  int factorizations_ = 0;
  bool reuse_ = true, reused_ = false;
};

}  // namespace fairshape::qp
