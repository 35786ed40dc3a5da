// A globalized solver of the length problem of Sauvage, Hahmann and Bonneau, "Length preserving
// multiresolution editing of curves" (eq. 2), not in the paper: a trust-region Newton method on
// the set of curves with the reference lengths. The paper's
// linearization and its Newton variant look for stationary points and, on Figure 1's edit,
// stop at constrained saddles at every β; this solver
//   1. retracts the start onto the lengths (Gauss–Newton, length_manifold.h) — a start that
//      cannot be retracted ends `infeasible`;
//   2. each iteration solves the KKT system of the Lagrangian's Hessian W = Q ⊗ I₃ + Σλ_r∇²f_r
//      (λ least squares) shifted by σI, σ ≥ 0 the smallest shift that makes the reduced
//      Hessian Zᵀ(W + σI)Z positive definite (inertia control: the LDLᵀ pivots' inertia of the
//      optimized KKT factor; the dense reduced Hessian up to `dense_limit` points only when
//      second_order: dense asks for it), so
//      the step s (tangent: J s = 0) minimizes a convex model and never heads for a saddle;
//   3. at negative curvature adds the eigenvector d of the smallest eigenvalue (the "hard case"
//      of Moré and Sorensen, "Computing a trust region step", 1983) to fill the radius Δ, so a
//      saddle is left even where the gradient vanishes (a planar curve's out-of-plane modes);
//   4. retracts X + s and accepts by ρ = actual / predicted decrease of F (Nocedal & Wright,
//      Algorithm 4.1; on the manifold: Absil, Baker and Gallivan, "Trust-region methods on
//      Riemannian manifolds", 2007), shrinking or growing Δ;
//   5. stops `converged` when the lengths, the stationarity and the second-order check hold,
//      `stalled` when the objective stopped decreasing over `stall_window` iterations or Δ
//      shrank to rounding, `max_iterations` at the budget.
// Feasible iterates mean the merit is F itself: the lengths hold to the retraction's tolerance
// at every accepted point.
#pragma once

#include "fairshape/curve_design/kkt_factor.h"
#include "fairshape/curve_design/length_solver.h"

namespace fairshape {

struct TrustRegionOptions {
  LengthTolerances tolerances;
  //! Initial radius in mean segment lengths per √(points): scale-free.
  double initial_radius = 1.0;
  //! Iterations without a decrease of F by more than rounding (or of the stationarity) before
  //! the solve stops `stalled`.
  int stall_window = 50;
  //! With tolerances.second_order Dense (only then: the default is the O(n) inertia at every
  //! size), up to this many points the reduced Hessian is formed densely each iteration (its smallest
  //! eigenvalue sets the shift, its eigenvector gives the negative-curvature step); above, the
  //! shift is raised until the optimized LDLᵀ's inertia is right (reference: until the step
  //! has positive curvature, which is weaker; the message says which).
  int dense_limit = 300;
  //! Above the dense limit: how many soft modes block inverse iteration follows per iteration
  //! (subspace_step.h); the step is the exact trust-region step in their span with the shifted
  //! Newton step. 1: one eigenvector by inverse iteration filling what the Newton step leaves
  //! of the radius (the method before; one negative mode left per iteration).
  int block_size = 8;
  //! Block inverse-iteration steps per iteration (the block is warm-started from the last).
  int block_steps = 3;
  //! While the inertia finds negative curvature: stop `stalled` (saying so) when within this
  //! many iterations F fell by less than progress_decrease·|F|, the stationarity by less than a
  //! tenth and the negative-eigenvalue count by less than half. 0: off (the budget decides).
  int progress_window = 20;
  double progress_decrease = 1e-2;
  KktMethod kkt = KktMethod::Direct;
  Backend backend = kFastestBackend;
};

class TrustRegionLengthSolver final : public LengthSolver {
 public:
  explicit TrustRegionLengthSolver(TrustRegionOptions o) : o_(o) {}
  LengthSolveReport solve(const LengthProblem& problem, const MatrixX3& start) const override;
  const LengthTolerances& tolerances() const override { return o_.tolerances; }
  bool takes_dense_rows() const override { return true; }  // bordered onto the banded KKT

 private:
  TrustRegionOptions o_;
};

}  // namespace fairshape
