// What every constrained solver of src/qp checks before it calls an answer converged (issue
// 23: conflicting or ill-posed constraints never give a silent answer):
//   - the rows are scaled to unit norm first, so "dependent" and "met" mean the same for a
//     point row, a tangent row and a curve row, whatever their units;
//   - the constraints must be met: ‖D(A p − b)‖∞ ≤ constraint_tolerance × the size of what
//     is constrained (D the row scaling), else `constraints_unmet` (inconsistent rows get a
//     least-squares fit, reported with its residual);
//   - the constraints must be well posed: the condition number of the constraints' Schur
//     complement S = Â (H + ρÂᵀÂ)⁻¹ Âᵀ (Â the unit rows, ρ = max diag H / max diag ÂᵀÂ), over
//     its directions above rank_tolerance² of the largest (the dependent ones are dropped),
//     at most max_condition, else `ill_conditioned`. 1/λ of S is the energy a unit move of
//     the targets along its eigenvector costs: two point constraints 1e-4 spans apart give
//     1.5e8, the shipped designs at most 5e4 (papers/welch-witkin/README.md).
#pragma once

#include <limits>
#include <string>

#include "fairshape/core/types.h"
#include "fairshape/qp/qp_solver.h"

namespace fairshape {
class Config;
}

namespace fairshape::qp {

struct ConstraintPolicy {
  double rank_tolerance = 1e-8;        // relative to the strongest direction of the unit rows
  double constraint_tolerance = 1e-10;  // relative to max(‖D b‖∞, ‖D A p‖∞)
  double max_condition = 1e7;          // of S; beyond: ill_conditioned
};
//! Reads rank_tolerance, constraint_tolerance and max_condition from a solver's options.
ConstraintPolicy read_constraint_policy(Config& cfg);

//! How far unit rows miss: max_i |(Âp − b̂)_i| / max(‖b̂‖∞, ‖Âp‖∞) (the worst row itself when
//! both are 0), what constraint_tolerance bounds.
double relative_unit_residual(const Eigen::MatrixXd& unit_Ap, const Eigen::MatrixXd& unit_b);

//! Unit-norm rows: scaled = D A, D = diag(1 / ‖a_i‖) (1 for a zero row, reported separately).
struct RowScaling {
  Eigen::VectorXd d;
  SparseMatrix scaled;
  int zero_rows = 0;
};
RowScaling scale_rows(const SparseMatrix& A);

//! Programs up to these sizes get a condition estimate from their own factorization of
//! H + ρÂᵀÂ (one sparse Cholesky, m solves, an m × m eigendecomposition); larger ones report
//! NaN (not estimated) and are judged on their residual alone.
inline constexpr Eigen::Index kConditionMaxRows = 2000;
inline constexpr Eigen::Index kConditionMaxUnknowns = 50000;

//! The rank of the unit rows at rank_tolerance (a dense column-pivoted QR on the unknowns they
//! reach), or −1 beyond kConditionMaxRows rows or 2e7 entries. S's eigenvalues cannot decide
//! it: S squares A's singular values, so a tolerance of 1e-8 on A is rounding noise on S.
int row_rank(const SparseMatrix& unit_rows, double rank_tolerance);

//! S's eigendecomposition restricted to its `rank` largest eigenvalues (S symmetric PSD): the
//! minimum-norm solve over the independent directions, and κ = λ₁ / λ_rank.
struct SchurSpectrum {
  Eigen::MatrixXd vectors;  // m × rank
  Eigen::VectorXd values;   // rank, descending
  double condition = 1;
  Eigen::MatrixXd solve(const Eigen::MatrixXd& rhs) const;  // minimum-norm S⁺ rhs on those directions
};
SchurSpectrum schur_spectrum(const Eigen::MatrixXd& S, int rank);
//! The ρ of the policy for H and unit rows Â.
double schur_rho(const SparseMatrix& H, const SparseMatrix& unit_rows);

//! S's spectrum for a program (from analyze), and what it says about a solution.
struct ConstraintConditioning {
  SchurSpectrum spectrum;
  double rho = 1;
  bool estimated = false;  // false: too large to estimate (or H + ρÂᵀÂ not positive definite)
  double condition() const { return estimated ? spectrum.condition : std::numeric_limits<double>::quiet_NaN(); }
  //! The share of the energy the constraints impose (λᵀSλ, λ the multipliers of the unit rows
  //! at the solution p, one column per coordinate) that sits in S's directions weaker than
  //! 1/max_condition of the strongest. A high condition alone is harmless when the targets
  //! are consistent with a smooth answer (dense curve samples moved rigidly); ill-posed
  //! constraints put their energy there (two close points pulled apart: all of it).
  double weak_share(const SparseMatrix& H, const SparseMatrix& unit_rows, const Eigen::MatrixXd& f, const Eigen::MatrixXd& unit_b,
                    const Eigen::MatrixXd& p, double max_condition) const;
};
//! S for H and unit rows Â (factoring H + ρÂᵀÂ) over its row_rank directions; not estimated
//! beyond the sizes above or when H + ρÂᵀÂ is not positive definite.
ConstraintConditioning constraint_conditioning(const SparseMatrix& H, const SparseMatrix& unit_rows, double rank_tolerance);

//! What assess() judges a solution of `H`, `f` and the rows against.
struct AssessedProgram {
  const SparseMatrix& H;
  const Eigen::MatrixXd& f;
  const SparseMatrix& A;  // the original rows
  const Eigen::MatrixXd& b;
  const RowScaling& rows;
  const ConstraintConditioning& conditioning;
};
//! Sets out.summary's termination and message from the policy: converged only when the rows
//! are met to tolerance and well posed (condition above max_condition with more than
//! kMaxWeakShare of the constraint energy in the weak directions: ill_conditioned). Fills
//! out.constraint_residual (‖A p − b‖_F, original rows) and out.condition_estimate.
void assess(QpReport& out, const AssessedProgram& program, const ConstraintPolicy& policy);
inline constexpr double kMaxWeakShare = 0.1;

}  // namespace fairshape::qp
