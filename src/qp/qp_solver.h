// One interface for the solvers of a QuadraticProgram (§4.3 of Welch & Witkin), registered by
// name with a reference and an optimized back end:
//   kkt         the Lagrange augmented system (eq. 9), dependent rows dropped first;
//   qr_penalty  the penalty least squares [μA; K] (eq. 10) by sparse QR, with Van Loan's
//               iterative refinement of the constraint residual;
//   range_space CHOLMOD on H + ρAᵀA and the small Schur complement of the constraints, whose
//               factor is updated in place when constraint rows are added or removed;
//   paper       Boier-Martin et al. §4.3's split: the unknowns the rows reach from the
//               minimum-norm least-squares solution of A p = b, then fixed; the others from
//               a linear solver (`free_solver`) — not the QP's minimizer, the paper's answer.
// analyze() pays for everything that depends on H and A; solve() takes new right-hand sides
// (a drag: same constraints, new targets).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "fairshape/core/registry.h"
#include "fairshape/qp/quadratic_program.h"
#include "fairshape/solver/solver.h"

namespace fairshape::qp {

struct QpReport {
  Eigen::MatrixXd p;  // n × k
  //! The outcome in the vocabulary of every solver (core/summary.h): termination, iterations
  //! (1 for the direct solvers), message (dropped rows, least-squares fallbacks, warnings).
  SolveSummary summary;
  int dropped_rows = 0;
  double constraint_residual = 0;  // ‖A p − b‖_F over every row
  double condition_estimate = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> residual_history;  // qr_penalty: the residual after each refinement step
};

//! What an iterative QP solve (the split of Boier-Martin et al. §4.3) may be given; the
//! direct solvers ignore it.
struct QpSolveOptions {
  const Eigen::MatrixXd* initial = nullptr;  // n × k: the start of the iteration
  IterationCallback callback;                // sees the full n × k iterate
  //! Split: the constrained unknowns take the least change from `initial` that meets their
  //! rows (a prolongated coarse solution keeps its shape), not the minimum-norm values.
  bool nearest_to_initial = false;
  //! Split: measure constraint_residual (a product with A; a cascade's intermediate levels
  //! skip it). Not measured: NaN.
  bool measure_residual = true;
};

class QpSolver {
 public:
  virtual ~QpSolver() = default;
  //! \throw InvalidInput for an invalid program; SolverError when a factorization fails.
  virtual void analyze(const QuadraticProgram& qp) = 0;
  //! The minimizer for new f and b (same H and A as analyze()).
  virtual QpReport solve(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b) = 0;
  virtual QpReport solve(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b, const QpSolveOptions&) { return solve(f, b); }
  //! Seconds of the last analyze() (factorization), for sweeps.
  double analyze_seconds() const { return analyze_s_; }

 protected:
  double analyze_s_ = 0;
};

using QpSolverRegistry = Registry<QpSolver>;
void register_qp_solvers(QpSolverRegistry& r);  // both back ends of every solver
const QpSolverRegistry& qp_solver_registry();

}  // namespace fairshape::qp
