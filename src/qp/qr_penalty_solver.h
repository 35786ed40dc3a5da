// The penalty method of Welch & Witkin eq. 10: minimize ‖K p − k‖² + ‖μ(A p − b)‖² through a
// sparse QR of the stacked [μA; K] (optimized SuiteSparseQR, reference Eigen SparseQR), never
// forming AᵀA. By default only R is used (Björck's corrected semi-normal equations: two
// triangular solves and one correction, so f need not come as Kᵀk); with `orthogonal` the
// constraint targets go through Q as a true least-squares solve.
// Van Loan's weighting method then refines the constraint residual with the same R: the
// target b is shifted by the remaining residual, `refinement_steps` times; each step shrinks
// ‖A p − b‖ by roughly the factor 1/(1 + μ²σ²) (σ the constraint-energy scale ratio).
// μ is relative: the constraint rows are weighted μ·√(max diag H)/max|A_ij|, so μ = 1 puts
// them on the energy's scale whatever the units.
#pragma once

#include <functional>
#include <memory>

#include "core/backend.h"
#include "qp/qp_solver.h"

namespace fairshape::qp {

struct QrPenaltyOptions {
  double mu = 1e3;
  int refinement_steps = 3;
  //! true: keep Q and solve through it (accurate to cond·ε, slow: Q of the tall [μA; K] is
  //! large); false: R alone, corrected semi-normal equations (fast, cond²·ε before correction).
  bool orthogonal = false;
};

class QrPenaltySolver final : public QpSolver {
 public:
  QrPenaltySolver(Backend backend, QrPenaltyOptions options);
  ~QrPenaltySolver() override;
  void analyze(const QuadraticProgram& qp) override;
  QpReport solve(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b) override;
  //! The absolute weight of the constraint rows (μ times the scale ratio).
  double weight() const { return weight_; }

 private:
  Eigen::MatrixXd semi_normal_solve(const Eigen::MatrixXd& rhs) const;
  Eigen::MatrixXd normal_product(const Eigen::MatrixXd& p) const;  // (KᵀK + w²AᵀA) p

  Backend backend_;
  QrPenaltyOptions options_;
  SparseMatrix H_, A_, At_, R_, Rt_;
  Eigen::VectorXi permutation_;  // column c of M P is column permutation_[c] of M
  Eigen::Index rows_ = 0;        // of M = [μA; K]
  std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)> least_squares_;  // argmin ‖M p − rhs‖ through Q
  double weight_ = 1;
  int rank_ = 0;
  double condition_ = 0;
};

//! A K with KᵀK = H for a PSD H that came without its sum-of-squares form: K = D^½ Lᵀ P from
//! the LDLᵀ of H + δI, δ = 1e-12·max diag H (a documented, negligible bias).
SparseMatrix square_root_of(const SparseMatrix& H);

}  // namespace fairshape::qp
