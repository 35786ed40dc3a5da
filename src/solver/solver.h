// One interface for every linear solver of the reduced system A x = b (A symmetric,
// b with one column per coordinate). analyze() does the work that depends only on A
// (factorization, colouring), so a sweep over right-hand sides or edits pays it once.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "core/registry.h"
#include "core/types.h"

namespace fairshape {

// Converged: the residual tolerance was met; EnergyStalled: the energy stopped decreasing
// (energy_tolerance); MaxIterations: the iteration cap, which is the paper's fixed count when
// both tolerances are 0.
enum class Termination { Converged, EnergyStalled, MaxIterations, NumericalFailure, InvalidInput };
std::string_view to_string(Termination t);

struct SolveSummary {
  Termination termination = Termination::NumericalFailure;
  int iterations = 0;
  double residual = -1;  // relative: ‖b − A x‖ / ‖b‖
  std::string message;
  //! Seconds spent observing the iterations (energies, callbacks, iterate copies for them):
  //! callers subtract it, so a monitored solve is timed like an unmonitored one.
  double observe_s = 0;
};

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

class Solver {
 public:
  virtual ~Solver() = default;
  //! Multilevel solvers need the transfer operators of a hierarchy; the others ignore them.
  virtual bool uses_levels() const { return false; }
  virtual void set_levels(std::shared_ptr<const LevelOperators>, const LevelSelection&) {}
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
