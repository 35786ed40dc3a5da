// A baseline without the paper's machinery: local-global projection as in ShapeOp / projective
// dynamics (Bouaziz et al. 2014), the usual way position-based tools keep edge lengths. Each
// constraint is a projection — a segment onto the sphere of its reference length, a pin onto
// its target — held by a quadratic penalty of weight w: the local step projects every segment
// of the current curve, the global step minimizes F(X) + w/2 Σ |D_c X − p_c|² with one
// factorization of Q + w Σ D_cᵀ D_c made once. It meets the lengths only as w → ∞ and does not
// reach the constrained problem's stationary points, which is what the comparison measures
// (papers/sauvage/README.md, "Baseline"): it ends max_iterations or stalled with the length
// error it reached, never converged unless the tolerances are met.
#pragma once

#include "fairshape/curve_design/length_solver.h"

namespace fairshape {

struct ProjectionOptions {
  LengthTolerances tolerances;
  double weight = 1e4;    // w relative to the largest diagonal entry of the objective's Hessian Q
  int stall_window = 500;  // iterations without the constraint error falling by 0.1 % before 'stalled'
};

class ProjectionLengthSolver final : public LengthSolver {
 public:
  explicit ProjectionLengthSolver(ProjectionOptions o) : o_(o) {}
  //! Constraints it cannot project (anything but segment lengths and pins) end invalid_input.
  LengthSolveReport solve(const LengthProblem& problem, const MatrixX3& start) const override;
  const LengthTolerances& tolerances() const override { return o_.tolerances; }

 private:
  ProjectionOptions o_;
};

}  // namespace fairshape
