// The set of curves that satisfy a length problem's constraint rows (every segment of its
// reference length, pins held), treated as a manifold: the least-squares multipliers of a
// point, and the retraction that brings a curve back onto the set. The globalized solver
// (trust_region_length_solver.h) moves along the set's tangent space and retracts; the tests
// use the same retraction to verify a minimum independently of any solver.
#pragma once

#include <string>

#include "fairshape/core/types.h"
#include "fairshape/curve_design/length_problem.h"

namespace fairshape {

//! λ minimizing |∇F(X) + J(X)ᵀλ| (J Jᵀ λ = −J ∇F): the multipliers a point has whether or not
//! a solver computed them. Interleaved unknowns, like constraint_jacobian.
Eigen::VectorXd least_squares_multipliers(const LengthProblem& p, const MatrixX3& X);

//! The Lagrangian's Hessian W = Q ⊗ I₃ + Σ_r λ_r ∇²f_r over interleaved unknowns (3·point + c).
SparseMatrix lagrangian_hessian(const LengthProblem& p, const Eigen::VectorXd& lambda);

struct Retraction {
  MatrixX3 points;
  double length_error = 0;  // max relative segment-length error reached
  double pin_error = 0;
  int iterations = 0;
  bool reached = false;     // both errors below the tolerance asked
};

//! Gauss–Newton onto f(X) = 0 by least-norm corrections X ← X − Jᵀ(JJᵀ)⁻¹f (no objective: the
//! nearest-to-first-order point of the set, a retraction in the sense of Absil, Mahony and
//! Sepulchre, "Optimization algorithms on matrix manifolds", §4.1), rows scaled to be
//! dimensionless, Levenberg–Marquardt damped (J Jᵀ + μ diag) whenever a correction does not
//! lower |f|. Stops at `tolerance` (relative, as max_relative_length_error), when no damping
//! lowers |f| any more (rounding, or no solution nearby), or after `max_iterations` trials.
Retraction retract(const LengthProblem& p, const MatrixX3& X, double tolerance, int max_iterations = 50);

//! A start far from the lengths (an over-stretched drag): retract, and when that fails follow
//! the Newton homotopy f(X) = (1 − t) f(X₀) from t = 0 (X₀ itself) to 1 by retractions.
Retraction restore(const LengthProblem& p, const MatrixX3& X, double tolerance, int max_iterations = 2000);

//! The length error a solve can be asked for: max relative segment-length rounding of a curve
//! of X's extent, ε · (largest |coordinate| / shortest segment), times a safety factor. It grows
//! with the point count (segments shrink) and is scale-free (a curve ×1000 has the same floor).
double length_rounding_floor(const LengthProblem& p, const MatrixX3& X);

//! The tolerance a solver uses: the one asked, or the rounding floor when that is larger (the
//! message says so: "tolerance raised to the rounding floor").
double attainable_length_tolerance(const LengthProblem& p, const MatrixX3& X, double asked);

}  // namespace fairshape
