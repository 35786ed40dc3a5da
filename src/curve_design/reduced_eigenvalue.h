// The smallest eigenvalue of the reduced Hessian Zᵀ W Z (second_order.h) without forming it:
// bisection on the inertia of the banded KKT factor (kkt_factor.h). By Sylvester's law the LDLᵀ
// of [W − tI, Jᵀ; J, 0] has m + #{eigenvalues of Zᵀ W Z below t} negative pivots (Z orthonormal,
// so Zᵀ(W − tI)Z = Zᵀ W Z − tI), so each factorization answers "is λ_min below t?" exactly up to
// rounding, in O(n) on the banded order. The bracket it returns is a guarantee, not an estimate's
// error bar. At a minimum Lanczos on the inverse of the factor at 0 (a Ritz value: an upper
// bound) and a probe or two just below it close the bracket in a handful of factorizations;
// otherwise bisection, O(n · (log log(scale/floor) + log(1/tolerance))). The constraint rows are the
// problem's own, so a planar problem (an InPlane row per point, curve_plane.h) is judged in its
// plane, as the dense check does (papers/sauvage/README.md, "Second-order checks cheaper than the
// solve").
#pragma once

#include "fairshape/core/types.h"
#include "fairshape/curve_design/length_problem.h"

namespace fairshape {

struct ReducedEigenvalueBracket {
  bool ok = false;          // false: a factorization failed, or dependent rows (no multipliers)
  double lower = 0, upper = 0;  // λ_min(Zᵀ W Z) ∈ [lower, upper]
  double scale = 0;         // the Gershgorin bound of |W|: every |eigenvalue| of Zᵀ W Z is below it
  int factorizations = 0;
  double estimate() const { return 0.5 * (lower + upper); }
};

//! Relative width of the bracket asked by default: two digits of the reported eigenvalue (what
//! runs.csv and the README quote; the verdict does not depend on it).
inline constexpr double kReducedEigenvalueTolerance = 1e-2;
//! Below this fraction of `scale` an eigenvalue is rounding: the bracket stops at that width.
inline constexpr double kReducedEigenvalueFloor = 1e-12;

//! λ_min of Zᵀ W Z at X, W the Lagrangian's Hessian with the least-squares multipliers of X
//! (length_manifold.h): the bracket is narrowed until upper − lower ≤ max(relative_tolerance ·
//! max(|lower|, |upper|), kReducedEigenvalueFloor · scale).
ReducedEigenvalueBracket smallest_reduced_eigenvalue(const LengthProblem& p, const MatrixX3& X,
                                                     double relative_tolerance = kReducedEigenvalueTolerance);

//! The unit tangent direction (J d = 0) of that eigenvalue, by inverse iteration (Golub & Van
//! Loan §8.2.2) with the factor of W − μI, μ a bracket's width below its lower end (so the shifted
//! reduced Hessian is positive definite and λ_min's eigenvector dominates); empty when a
//! factorization or solve fails.
MatrixX3 smallest_reduced_eigenvector(const LengthProblem& p, const MatrixX3& X, const ReducedEigenvalueBracket& bracket,
                                      int iterations = 20);

}  // namespace fairshape
