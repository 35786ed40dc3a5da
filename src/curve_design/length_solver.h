// Solvers of the length-constrained problem (length_problem.h): the linearized Lagrange loop
// of Sauvage et al. §3, an exact augmented-Lagrangian solve over Ceres and a globalized trust
// region that ends at local minima. Registered by
// name, each with reference and optimized back ends where they differ.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "fairshape/core/registry.h"
#include "fairshape/core/summary.h"
#include "fairshape/core/types.h"
#include "fairshape/curve_design/length_problem.h"

namespace fairshape {

struct LengthSolveStep {
  int solves = 0;            // linear solves so far
  double length_error = 0;   // max relative segment-length error after them
  double stationarity = 0;   // LengthProblem::stationarity-style measure (solver's estimate)
  double seconds = 0;
  double objective = 0;      // the §3 objective F at the iterate
};

struct LengthSolveReport {
  MatrixX3 points;
  //! The outcome in every solver's vocabulary (core/summary.h): converged, max_iterations (the
  //! solve budget before the tolerances), not_a_minimum (a constrained saddle: stationary, but
  //! the reduced Hessian has a negative eigenvalue), stalled (no progress over the stall
  //! window), infeasible (the lengths could not be restored from the start) or
  //! numerical_failure (a KKT system that cannot be factored, non-finite values, Ceres
  //! failing); iterations = solves; message says why.
  SolveSummary summary;
  bool converged() const { return summary.termination == Termination::Converged; }
  int solves = 0;            // linear systems solved (Ceres: its inner Gauss-Newton steps)
  int outer_iterations = 0;  // linearizations, or augmented-Lagrangian rounds
  double length_error = 0, pin_error = 0;
  //! The smallest eigenvalue of the reduced Hessian at the answer (curve_design/second_order.h;
  //! NaN when not checked: not converged, second_order off, or the check failed).
  double min_reduced_hessian_eig = std::numeric_limits<double>::quiet_NaN();
  int saddle_escapes = 0;  // negative-curvature steps taken away from saddles found on the way (trust_region: accepted ones)
  std::vector<LengthSolveStep> history;
};

// How a stationary answer is judged at second order (second_order.h; papers/sauvage/README.md,
// "Second-order checks cheaper than the solve"): Inertia, the banded KKT factor's inertia for the
// verdict and bisection on it for the smallest eigenvalue, O(n) at any size; Dense, the reduced
// Hessian's full eigen-decomposition, O(n³), up to kSecondOrderDenseLimit points; Off, no check
// (the answer is first-order only, and says so).
enum class SecondOrderMode { Inertia, Dense, Off };

// Stopping rule shared by the solvers.
struct LengthTolerances {
  double length = 1e-10;       // max relative segment-length error (the floor grows like n·ε)
  double stationarity = 1e-8;  // 0: stop on lengths alone, as the paper does
  int max_solves = 200;
  SecondOrderMode second_order = SecondOrderMode::Inertia;
};

class LengthSolver {
 public:
  virtual ~LengthSolver() = default;
  //! Never throws for numerical failure: the report's summary says numerical_failure and why.
  virtual LengthSolveReport solve(const LengthProblem& problem, const MatrixX3& start) const = 0;
  virtual const LengthTolerances& tolerances() const = 0;
  //! Whether it solves problems with a dense row (a total length, LengthProblem::has_dense_rows):
  //! the KKT-based solvers border it; the others refuse (invalid_input) rather than ignore it.
  virtual bool takes_dense_rows() const { return false; }
};

using LengthSolverRegistry = Registry<LengthSolver>;
//! linearized (reference: block KKT + SparseLU each solve; optimized: per-point ordering,
//! one symbolic analysis, banded LDLᵀ, TBB-parallel value updates), ceres and trust_region
//! (globalized; trust_region_length_solver.h).
void register_length_solvers(LengthSolverRegistry& r);

}  // namespace fairshape
