// Solving Sauvage, Hahmann and Bonneau's eq. 2 ("Length preserving multiresolution editing of
// curves", §3) on the edit's support only (`solve_region: support`).
//
// The paper's optimization runs over the whole curve: its smoothness term then reshapes parts
// the user never touched (by 3e-3 to 4e-2 of the curve's size in Figures 3 and 4). Here the
// unknowns are the support's points (edit_support.h); every other point keeps its place in
// C_A. The curve is cut at runs of ≥ 2 fixed points into windows, each an open sub-curve of
// the support's points plus the fixed neighbour on each side, pinned (a single fixed point
// between two support runs stays in the window, pinned). Stencils that reach outside a window
// keep the fixed points' share as a constant (CurveStencil::constant), so the objective is the
// whole curve's restricted to the free points — the same minimizers on the support — and only
// the segment lengths with a free end are constraints (two pinned neighbours would make their
// length row linearly dependent on the pins). A support covering the whole curve is one
// window: the paper's problem, with the fixed single points pinned.
#pragma once

#include <memory>
#include <vector>

#include "fairshape/curve_design/length_problem.h"
#include "fairshape/curve_design/length_solver.h"

namespace fairshape {

struct EditWindow {
  std::vector<int> points;  // curve indices, in window order
  std::unique_ptr<LengthProblem> problem;
};

//! The windows of `whole` (the whole-curve problem of the edit) for a fine-level support mask.
//! Empty when every point is free and no pin is needed: solve `whole` itself.
//! \throw InvalidInput as LengthProblem (pins farther apart than the curve between them), and
//! for constraints other than segment lengths and pins (tangents are not mapped onto windows).
std::vector<EditWindow> edit_windows(const LengthProblem& whole, const std::vector<char>& support);

//! Solves every window from C_A (`whole.attractor()`) and puts the pieces back into one curve;
//! solves and iterations add up, the first window not converged decides the termination, the
//! smallest eigenvalue and the largest errors are reported.
LengthSolveReport solve_windows(const LengthProblem& whole, const std::vector<EditWindow>& windows,
                                const LengthSolver& solver);

}  // namespace fairshape
