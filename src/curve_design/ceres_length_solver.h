// The exact nonlinear problem of Sauvage, Hahmann and Bonneau, "Length preserving
// multiresolution editing of curves" (eq. 2) solved with Ceres: an augmented-Lagrangian loop
// whose every round is one Ceres least-squares solve of
//   Σ_t w_t E_t(X) + Σ_r [ λ_r g_r(X) + (μ/2) g_r(X)² ],   g_r = f_r / scale_r,
// followed by λ ← λ + μ g and, when the violation did not drop fourfold, μ ← 10 μ. Unlike the
// linearized loop it never linearizes the lengths: each round minimizes the true objective.
#pragma once

#include "fairshape/curve_design/length_solver.h"

namespace fairshape {

struct CeresOptions {
  LengthTolerances tolerances;
  double initial_penalty = 10;  // μ₀, relative to the objective's curvature (see .cpp)
  int max_rounds = 40;
  int threads = 1;
};

class CeresLengthSolver final : public LengthSolver {
 public:
  explicit CeresLengthSolver(CeresOptions o) : o_(o) {}
  LengthSolveReport solve(const LengthProblem& problem, const MatrixX3& start) const override;
  const LengthTolerances& tolerances() const override { return o_.tolerances; }

 private:
  CeresOptions o_;
};

}  // namespace fairshape
