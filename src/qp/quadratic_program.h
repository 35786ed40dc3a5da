// The linearly constrained quadratic program of Welch & Witkin §4.3 (eq. 8), the common
// ground of every surface and curve problem in fairshape:
//   minimize ½ pᵀ H p − pᵀ f   subject to   A p = b,
// with one column of p, f and b per coordinate (x, y, z share H and A).
#pragma once

#include <memory>
#include <string>

#include "fairshape/core/types.h"
#include "fairshape/solver/level_operators.h"

namespace fairshape::qp {

struct QuadraticProgram {
  SparseMatrix H;      // n × n, symmetric positive semi-definite (or empty: see borrowed_H)
  Eigen::MatrixXd f;   // n × k
  SparseMatrix A;      // m × n constraint rows (dependent and even inconsistent rows allowed)
  Eigen::MatrixXd b;   // m × k
  //! Optional sum-of-squares form of the energy, KᵀK = H (the QR-penalty solver factors [μA; K]
  //! instead of H); empty: derived from H when needed.
  SparseMatrix K;
  //! Optional levels below the program's unknowns, for a multilevel solver of the free
  //! unknowns (the split solver with multigrid).
  std::shared_ptr<const LevelOperators> levels;
  //! H lent by a caller that keeps it alive through analyze() and solve(), instead of a copy
  //! in H (the edit's H is 1.3 GB at 4.5M unknowns). Solvers read hessian(), never H.
  const SparseMatrix* borrowed_H = nullptr;
  const SparseMatrix& hessian() const { return borrowed_H ? *borrowed_H : H; }
};

//! \throw InvalidInput naming the mismatched or non-finite part.
void validate(const QuadraticProgram& qp);
//! ½ Σ_c p_cᵀ H p_c − f_cᵀ p_c.
double objective(const QuadraticProgram& qp, const Eigen::MatrixXd& p);
//! ‖A p − b‖_F.
double constraint_residual(const SparseMatrix& A, const Eigen::MatrixXd& b, const Eigen::MatrixXd& p);

}  // namespace fairshape::qp
