// The linearized Lagrange loop of Sauvage, Hahmann and Bonneau, "Length preserving
// multiresolution editing of curves" (§3, eq. 3–4): linearize every constraint at the current
// curve, solve the KKT system for the next curve and the multipliers, repeat until the
// lengths (and, optionally, stationarity) meet the tolerances.
#pragma once

#include "fairshape/curve_design/kkt_factor.h"
#include "fairshape/curve_design/length_solver.h"

namespace fairshape {

struct LinearizedOptions {
  LengthTolerances tolerances;
  // paper: W = Q (the published system; converges linearly). newton: W = Q + Σλ_r∇²f_r with
  // the previous multipliers (the Lagrangian's Hessian: quadratic convergence near the
  // solution), used once the length error is below newton_switch. Far from the lengths that
  // W can be indefinite and full Newton steps diverge (measured: the Figure 1 edit blows up
  // from a 12% error), so the paper's steps bring the curve close first.
  bool newton = false;
  double newton_switch = 1e-3;
  // The paper takes every full step. Full steps can cycle (measured: Figure 4's first loop
  // settles into a 2-cycle at 4.2% length error), so by default a step is shortened until
  // the ℓ1 merit F + ν Σ|f_r| decreases (Armijo backtracking, Nocedal & Wright §18.3).
  bool line_search = true;
  // Stationary is not minimal: a converged point whose reduced Hessian has a negative
  // eigenvalue (curve_design/second_order.h) is left along that direction this many times at
  // most before the solve reports not_a_minimum.
  // 0 by default: the paper's method is judged as published (a saddle ends not_a_minimum).
  int saddle_escapes = 0;
  // Solves within which the distance to the tolerances must fall by a tenth; else `stalled`.
  int stall_window = 1000;
  KktMethod kkt = KktMethod::Direct;
  double minres_tolerance = 1e-13;
  Backend backend = kFastestBackend;
};

class LinearizedLengthSolver final : public LengthSolver {
 public:
  explicit LinearizedLengthSolver(LinearizedOptions o) : o_(o) {}
  LengthSolveReport solve(const LengthProblem& problem, const MatrixX3& start) const override;
  const LengthTolerances& tolerances() const override { return o_.tolerances; }
  bool takes_dense_rows() const override { return true; }  // bordered onto the banded KKT

 private:
  LinearizedOptions o_;
};

}  // namespace fairshape
