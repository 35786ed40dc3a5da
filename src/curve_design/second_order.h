// Second-order optimality of a length-constrained solve. A point where the
// lengths hold and ∇F + Jᵀλ = 0 may still be a constrained saddle: Sauvage, Hahmann and
// Bonneau's linearization and its Newton variant only look for stationary points. At a local
// minimum the Lagrangian's Hessian W = Q ⊗ I₃ + Σ_r λ_r ∇²f_r is positive semidefinite on the
// tangent space of the constraints, null(J): the reduced Hessian Zᵀ W Z (Z an orthonormal basis
// of null(J)) has no negative eigenvalue (Nocedal & Wright, Theorem 12.5). λ is the
// least-squares multiplier of the point itself, so every solver's answer is judged the same way.
#pragma once

#include <string>

#include "fairshape/core/types.h"
#include "fairshape/curve_design/length_problem.h"
#include "fairshape/curve_design/length_solver.h"

namespace fairshape {

struct SecondOrderCheck {
  bool checked = false;          // false: not made (see message)
  double min_eigenvalue = 0;     // of Zᵀ W Z (inertia: the bisection bracket's midpoint)
  double max_abs_eigenvalue = 0; // dense: exact; inertia: a bound (Gershgorin on W)
  double min_eigenvalue_error = 0;  // inertia: half the bracket's width, a guarantee; dense: 0
  int negative_count = -1;       // inertia: eigenvalues below −shift (the verdict); −1: dense
  MatrixX3 direction;            // Z times its eigenvector (unit norm): the negative-curvature direction
  std::string message;
  //! Dense: no eigenvalue below −tolerance · max |eigenvalue| (relative: Q's scale is the user's
  //! weights). Inertia: no eigenvalue below the shift (tolerance · Q's largest diagonal entry).
  bool is_minimum(double tolerance) const {
    if (!checked) return true;
    if (negative_count >= 0) return negative_count == 0;
    return min_eigenvalue >= -tolerance * max_abs_eigenvalue;
  }
};

//! Points up to this many may be checked densely (3N unknowns: an O((3N)³) eigen-solve, about a
//! second at the limit); second_order: dense is refused above it.
inline constexpr int kSecondOrderDenseLimit = 600;

//! The dense check: Zᵀ W Z formed and fully eigen-decomposed (SecondOrderMode::Dense).
SecondOrderCheck check_second_order(const LengthProblem& p, const MatrixX3& X);

//! The default tolerance of is_minimum: eigenvalues that are rounding of the largest.
inline constexpr double kSecondOrderTolerance = 1e-8;

//! How many eigenvalues of Zᵀ W Z lie below −shift (default: kSecondOrderTolerance · Q's
//! largest diagonal entry), from the inertia of the LDLᵀ factor of the KKT matrix with W + shift·I
//! (kkt_factor.h: negative pivots beyond one per constraint row). O(n) on the banded order, so
//! it works at any size. The optimized banded factor is used whatever the solver's back end (a
//! check, not a solve). −1 when the factorization fails or gives no inertia.
int reduced_hessian_negative_count(const LengthProblem& p, const MatrixX3& X, double shift = -1);

//! The O(n) check at any size (SecondOrderMode::Inertia): the verdict from
//! reduced_hessian_negative_count, the smallest eigenvalue bracketed by inertia bisection
//! (reduced_eigenvalue.h), and at negative curvature, when `want_direction`, its eigenvector.
SecondOrderCheck check_second_order_by_inertia(const LengthProblem& p, const MatrixX3& X, bool want_direction);

//! The check `mode` asks for: Dense above kSecondOrderDenseLimit points falls back to inertia
//! (the message says so; a run refuses that configuration before solving); Off: not checked.
SecondOrderCheck second_order_check(const LengthProblem& p, const MatrixX3& X, SecondOrderMode mode, bool want_direction);

//! A converged report judged at second order: its min_reduced_hessian_eig set, and at a saddle
//! its termination not_a_minimum with the eigenvalue in the message. Without a stationarity
//! tolerance (lengths alone) the eigenvalue is only reported. `made`: a check the solver already
//! made at rep.points (not repeated). Returns the check.
SecondOrderCheck judge_second_order(const LengthProblem& p, LengthSolveReport& rep, bool stationarity_asked,
                                    SecondOrderMode mode, const SecondOrderCheck* made = nullptr);

//! The config names of SecondOrderMode (inertia, dense, off).
const char* to_string(SecondOrderMode mode);

}  // namespace fairshape
