// The penalty method of Welch & Witkin eq. 10: minimize ‖K p − k‖² + ‖μ(A p − b)‖² through a
// sparse QR of the stacked [μA; K] (optimized SuiteSparseQR, reference Eigen SparseQR), never
// forming AᵀA. By default only R is used (Björck's corrected semi-normal equations: two
// triangular solves and one correction, so f need not come as Kᵀk); with `orthogonal` the
// constraint targets go through Q as a true least-squares solve.
// Van Loan's weighting method then refines the constraint residual with the same R: the
// target b is shifted by the remaining residual until the residual meets the policy's
// constraint_tolerance (qp/constraint_policy.h) and a step moves the answer by less than
// solution_tolerance, at most `refinement_steps` times per μ; each step shrinks ‖A p − b‖ by
// roughly 1/(1 + μ²σ²) (σ the constraint-energy scale ratio). When a step halves neither, μ
// grows tenfold (a new factorization), up to max_mu; a residual still above the tolerance is
// reported as constraints_unmet, an answer still moving as ill_conditioned, never as converged.
// Rows are scaled to unit norm and μ is relative: they are weighted μ·√(max diag H)/max|Â_ij|,
// so μ = 1 puts them on the energy's scale whatever the units.
#pragma once

#include <functional>
#include <memory>

#include "fairshape/core/backend.h"
#include "fairshape/qp/constraint_policy.h"
#include "fairshape/qp/qp_solver.h"

namespace fairshape::qp {

struct QrPenaltyOptions {
  double mu = 1e3;
  int refinement_steps = 10;  // at most, per μ
  double max_mu = 1e8;
  //! A refinement step that still moves the answer by more than this (max-norm, relative) is
  //! not the last: the residual alone can be met while weak directions are far off.
  double solution_tolerance = 1e-5;
  //! true: keep Q and solve through it (accurate to cond·ε, slow: Q of the tall [μA; K] is
  //! large); false: R alone, corrected semi-normal equations (fast, cond²·ε before correction).
  bool orthogonal = false;
  ConstraintPolicy policy;
  //! Keep the factorization across analyze() calls with the same H, K and A (a drag step).
  bool reuse_factorization = true;
};

class QrPenaltySolver final : public QpSolver {
 public:
  QrPenaltySolver(Backend backend, QrPenaltyOptions options);
  ~QrPenaltySolver() override;
  void analyze(const QuadraticProgram& qp) override;
  QpReport solve(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b) override;
  //! The absolute weight of the constraint rows (μ times the scale ratio) of the last factorization.
  double weight() const { return weight_; }
  //! Factorizations so far, and whether the last analyze() kept the previous one.
  int factorizations() const { return factorizations_; }
  bool reused_factorization() const { return reused_; }

 private:
  void factor(double mu);  // [μA; K] = Q R
  Eigen::MatrixXd penalty_solve(const Eigen::MatrixXd& f, const Eigen::MatrixXd& targets) const;
  Eigen::MatrixXd semi_normal_solve(const Eigen::MatrixXd& rhs) const;
  Eigen::MatrixXd normal_product(const Eigen::MatrixXd& p) const;  // (KᵀK + w²AᵀA) p

  Backend backend_;
  QrPenaltyOptions options_;
  SparseMatrix H_, A_, At_, R_, Rt_, K_;  // A_: the unit-norm rows of A_original_
  SparseMatrix A_original_;
  RowScaling scaling_;
  double mu_ = 0;
  ConstraintConditioning conditioning_;
  Eigen::VectorXi permutation_;  // column c of M P is column permutation_[c] of M
  Eigen::Index rows_ = 0;        // of M = [μA; K]
  std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)> least_squares_;  // argmin ‖M p − rhs‖ through Q
  double weight_ = 1;
  int rank_ = 0;
  double condition_ = 0;
  int factorizations_ = 0;
  bool reused_ = false;
};

//! A K with KᵀK = H for a PSD H that came without its sum-of-squares form: K = D^½ Lᵀ P from
//! the LDLᵀ of H + δI, δ = 1e-12·max diag H (a documented, negligible bias).
SparseMatrix square_root_of(const SparseMatrix& H);

}  // namespace fairshape::qp
