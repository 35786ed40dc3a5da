// The symmetric indefinite system of one linearized step of Sauvage, Hahmann and Bonneau,
// "Length preserving multiresolution editing of curves" (§3, eq. 4), generalized to 3D and
// to any constraint rows:  [ W  Jᵀ ] [X]   [r_x]
//                          [ J  0  ] [λ] = [r_λ],   W = Q ⊗ I₃ (+ Σ λ_r ∇²f_r, Newton).
// Unknowns in natural order: 3·point + coordinate, then one per constraint row.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "fairshape/core/backend.h"
#include "fairshape/curve_design/length_problem.h"

namespace fairshape {

class KktFactor {
 public:
  virtual ~KktFactor() = default;
  //! Factors (or, for the iterative method, stores) the system for rows evaluated at the
  //! current iterate; `newton_multipliers` (may be null) adds their constraint Hessians to W,
  //! `curvature_shift` ≥ 0 adds δ I to W (the modified Newton step of an indefinite W).
  //! \return false when the factorization failed (singular system).
  virtual bool factor(const std::vector<ConstraintRow>& rows, const Eigen::VectorXd* newton_multipliers,
                      double curvature_shift = 0) = 0;
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& rhs) = 0;
  virtual std::string last_error() const { return {}; }
  //! Negative pivots of the last LDLᵀ factorization, −1 when the factorization does not give
  //! them (SparseLU, MINRES). By Sylvester's law of inertia they are the KKT matrix's negative
  //! eigenvalues: m (one per independent constraint row) plus those of the reduced Hessian
  //! Zᵀ W Z (Gould, "On practical conditions for the existence and uniqueness of solutions to
  //! the general equality quadratic programming problem", 1985) — so m means W is positive
  //! definite on the constraints' tangent space.
  virtual int negative_pivots() const { return -1; }
};

enum class KktMethod { Direct, Minres };

//! Reference: the block system assembled from triplets each step and factored by SparseLU.
//! Optimized: unknowns ordered point by point (each constraint row after the last point it
//! touches), so the system is banded; its pattern and symbolic LDLᵀ analysis are made once
//! and each step only rewrites values (TBB) and refactors, then refines once against the
//! unregularized system. Minres: Eigen's MINRES on the same matrix (no preconditioner).
std::unique_ptr<KktFactor> make_kkt_factor(const LengthProblem& p, Backend backend, KktMethod method,
                                           double iterative_tolerance);

}  // namespace fairshape
