// minimize ½ Σ_c u_cᵀ H u_c − g_cᵀ u_c  subject to  u[fixed] = fixed_values
// (u is #V × 3: one column per coordinate, all sharing H), and its reduced form
// A u_free = b with A = H_ff and b = g_f − H_fc u_fixed, which is what linear solvers see.
#pragma once

#include <vector>

#include "fairshape/core/types.h"

namespace fairshape {

struct ConstrainedSystem {
  SparseMatrix H;
  Eigen::MatrixXd g;  // #V × 3
  std::vector<int> fixed;
  Eigen::MatrixXd fixed_values;  // #fixed × 3
};

struct ReducedSystem {
  SparseMatrix A;     // #free × #free, symmetric
  Eigen::MatrixXd b;  // #free × 3
  std::vector<int> free, fixed;
  Eigen::MatrixXd fixed_values;
  int n_full = 0;

  SparseMatrix coupling;   // H_fc: #free × #fixed
  Eigen::MatrixXd g_free;  // g_f

  //! New values of the fixed unknowns (same ids): b = g_f − H_fc u_c, A kept (a drag step).
  //! \throw InvalidInput for a count mismatch or non-finite values.
  void set_fixed_values(const Eigen::MatrixXd& values);
  //! The full #V × 3 solution from the free unknowns.
  Eigen::MatrixXd expand(const Eigen::MatrixXd& u_free) const { return expand(u_free, fixed_values); }
  //! The same with other values of the fixed unknowns (one row each, as many columns as u_free).
  Eigen::MatrixXd expand(const Eigen::MatrixXd& u_free, const Eigen::MatrixXd& values) const;
  //! The free unknowns of a full solution.
  Eigen::MatrixXd restrict_to_free(const Eigen::MatrixXd& u_full) const;
};

//! \throw InvalidInput when sizes disagree, a fixed id is out of range, or values are not finite.
ReducedSystem reduce(const ConstrainedSystem& s);
//! The same from H lent by the caller (no copy of H into a ConstrainedSystem).
ReducedSystem reduce(const SparseMatrix& H, const Eigen::MatrixXd& g, const std::vector<int>& fixed,
                     const Eigen::MatrixXd& fixed_values);
//! ½ Σ_c u_cᵀ H u_c − Σ_c g_cᵀ u_c, the objective of a ConstrainedSystem or an edit problem.
double quadratic_energy(const SparseMatrix& H, const Eigen::MatrixXd& g, const Eigen::MatrixXd& u);
//! diag(M, ..., M) with `copies` blocks: M acting on every coordinate of the stacked
//! unknowns [x; y; z] (the coupled system of normal constraints, multigrid on it).
SparseMatrix block_diagonal(const SparseMatrix& M, int copies);
//! The blocks one above the other (all with the same number of columns).
SparseMatrix stack_rows(const std::vector<const SparseMatrix*>& blocks);
//! ‖x − reference‖_F / ‖reference‖_F (or the absolute error when the reference is 0).
double relative_error(const Eigen::MatrixXd& x, const Eigen::MatrixXd& reference);
//! ‖b − A x‖_F / ‖b‖_F (or ‖b − A x‖_F when b = 0).
double relative_residual(const SparseMatrix& A, const Eigen::MatrixXd& b, const Eigen::MatrixXd& x);

}  // namespace fairshape
