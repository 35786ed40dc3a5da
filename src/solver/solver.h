// One interface for every linear solver of the reduced system A x = b (A symmetric,
// b with one column per coordinate). analyze() does the work that depends only on A
// (factorization, colouring), so a sweep over right-hand sides or edits pays it once.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "fairshape/core/registry.h"
#include "fairshape/core/summary.h"
#include "fairshape/core/types.h"

namespace fairshape {

struct IterationRecord {
  int iteration;
  double residual;
  double seconds;
  double energy;             // ½ xᵀA x − bᵀx of the system solved (NaN when not evaluated)
  const Eigen::MatrixXd* x;  // the current iterate, for snapshots
};
using IterationCallback = std::function<bool(const IterationRecord&)>;  // false stops the solve

struct LevelOperators;  // solver/level_operators.h
struct LevelSelection;

// The analysis contract. solve(A, …) answers for exactly the A it is given. When A is not the
// matrix analyzed — another size, sparsity pattern or any value — the solver analyzes A first;
// it never solves with another matrix's factor, colouring or multigrid levels. A solve with no
// analyze() before it analyzes on demand. So analyze() only moves the set-up out of the first
// (timed, repeated) solve; it is never required for a correct answer.
// Matrices are matched by value, never by address (callers refill one buffer with new values):
// a solver that keeps anything from analyze() remembers the matrix's MatrixFingerprint
// (solver/matrix_fingerprint.h) and compares it at every solve. That is one pass over A: noise
// next to a factorization, about one extra product with A (a sweep's worth) for an iterative solve.
// tests/unit/stale_factor_test.cpp holds every registered solver to this.
class Solver {
 public:
  virtual ~Solver() = default;
  //! Multilevel solvers need the transfer operators of a hierarchy; the others ignore them.
  virtual bool uses_levels() const { return false; }
  //! New levels discard the analysis: the next solve analyzes again.
  virtual void set_levels(std::shared_ptr<const LevelOperators>, const LevelSelection&) {}
  //! \throw InvalidInput when the solver cannot work on A (a multilevel solver without levels, or
  //! levels that do not fit A), from analyze() or from the solve that analyzes on demand.
  virtual void analyze(const SparseMatrix& A) = 0;
  //! On entry x holds the initial guess (iterative solvers warm-start from it).
  virtual SolveSummary solve(const SparseMatrix& A, const Eigen::MatrixXd& b, Eigen::MatrixXd& x,
                             const IterationCallback& cb = {}) = 0;
};

using SolverRegistry = Registry<Solver>;
void register_solvers(SolverRegistry& r);  // optimized back ends (src/solver)

}  // namespace fairshape

namespace fairshape::reference {
void register_solvers(SolverRegistry& r);  // reference back ends (reference/solver)
}  // namespace fairshape::reference
