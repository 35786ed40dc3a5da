// Unknowns pinned by a row of their own taken out of a quadratic program: a row a·p_j = b_i
// that reaches one unknown (a held vertex's coordinate) fixes p_j = b_i / a, so
//   minimize ½ pᵀHp − pᵀf  s.t.  A p = b
// over the rest F, with P the pinned unknowns, is the smaller program
//   minimize ½ p_Fᵀ H_FF p_F − p_Fᵀ (f_F − H_FP p_P)  s.t.  A_F p_F = b − A_P p_P
// over the rows left. It is the same minimizer, not an approximation (the elimination Boier-
// Martin et al. §4.3 apply to held vertices), and H_FF is positive definite once the pinned
// unknowns hold H's null space — where a Lagrange system whose H spans many orders of magnitude
// can look singular to an LU (papers/boier-martin/README.md, "KKT on badly scaled systems").
#pragma once

#include <vector>

#include "fairshape/core/types.h"
#include "fairshape/problem/constrained_system.h"

namespace fairshape::qp {

class PinnedReduction {
 public:
  //! H: n × n; A: m × n. The first row that pins an unknown pins it; a second one is left for
  //! the caller's check of every original row.
  PinnedReduction(const SparseMatrix& H, const SparseMatrix& A);
  bool any() const { return !pinned_.empty(); }
  int n_pinned() const { return static_cast<int>(pinned_.size()); }
  //! H_FF and the rows that still reach a free unknown, restricted to the free unknowns.
  const SparseMatrix& free_hessian() const { return energy_.A; }
  const SparseMatrix& free_rows() const { return A_F_; }
  //! The reduced program's right-hand sides for f (n × k) and b (m × k).
  Eigen::MatrixXd reduced_f(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b) const;
  Eigen::MatrixXd reduced_b(const Eigen::MatrixXd& b) const;
  //! The full solution from the free unknowns' values and the pinned ones' rows.
  Eigen::MatrixXd expand(const Eigen::MatrixXd& p_free, const Eigen::MatrixXd& b) const;

 private:
  Eigen::MatrixXd pinned_values(const Eigen::MatrixXd& b) const;  // |P| × k

  struct Pin {
    int unknown, row;
    double coefficient;
  };
  std::vector<Pin> pinned_;
  ReducedSystem energy_;   // H_FF (A), H_FP (coupling) and the free unknowns (free)
  std::vector<int> rows_;  // reduced row r is row rows_[r] of A
  SparseMatrix A_F_, A_P_;
};

}  // namespace fairshape::qp
