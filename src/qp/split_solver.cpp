#include <iomanip>
#include <sstream>
#include "fairshape/qp/split_solver.h"

#include <cmath>
#include <limits>

#include "fairshape/core/error.h"
#include "fairshape/core/timer.h"
#include "fairshape/problem/least_squares.h"
#include "fairshape/solver/independent_columns.h"

namespace fairshape::qp {

SplitSolver::SplitSolver(Solver& free_solver, Backend backend) : free_(free_solver), backend_(backend) {
  require_backend(backend);
}
SplitSolver::SplitSolver(std::unique_ptr<Solver> free_solver, Backend backend)
    : owned_(std::move(free_solver)), free_(*owned_), backend_(backend) {
  require_backend(backend);
}
SplitSolver::~SplitSolver() = default;

void SplitSolver::analyze(const QuadraticProgram& qp) {
  validate(qp);
  const Timer timer;
  n_ = qp.hessian().rows();
  A_ = qp.A;
  touched_ = reached_columns(A_);
  if (touched_.empty()) throw InvalidInput("paper: no constraint row reaches an unknown: the split has nothing to fix");
  const SparseMatrix pick = row_picker(A_.cols(), touched_);
  ls_ = std::make_unique<MinNormLeastSquares>(A_ * pick, backend_);
  lent_H_ = qp.borrowed_H;
  H_cc_ = lent_H_ ? SparseMatrix() : SparseMatrix(SparseMatrix(pick.transpose()) * qp.hessian() * pick);
  red_ = reduce(qp.hessian(), qp.f, touched_, Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(touched_.size()), qp.f.cols()));
  if (!red_.free.empty()) {
    if (free_.uses_levels()) {
      if (!qp.levels) throw InvalidInput("paper: a multilevel solver needs a hierarchy below the edit level");
      // The solver sees the reduced system: its finest unknowns are the free ones.
      free_.set_levels(qp.levels, {red_.free, static_cast<int>(n_ / qp.levels->prolongation.back().rows())});
    }
    free_.analyze(red_.A);
  }
  analyze_s_ = timer.seconds();
}

QpReport SplitSolver::solve(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b) { return solve(f, b, {}); }

double SplitSolver::constrained_energy(const Eigen::MatrixXd& f, const Eigen::MatrixXd& fixed) const {
  if (!lent_H_) {
    Eigen::MatrixXd f_c(static_cast<Eigen::Index>(touched_.size()), f.cols());
    for (std::size_t k = 0; k < touched_.size(); ++k) f_c.row(static_cast<Eigen::Index>(k)) = f.row(touched_[k]);
    return quadratic_energy(H_cc_, f_c, fixed);
  }
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(n_, f.cols());  // the fixed values in place, zero elsewhere
  for (std::size_t k = 0; k < touched_.size(); ++k) p.row(touched_[k]) = fixed.row(static_cast<Eigen::Index>(k));
  return quadratic_energy(*lent_H_, f, p);
}

QpReport SplitSolver::solve(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b, const QpSolveOptions& o) {
  FAIRSHAPE_ASSERT(ls_, "SplitSolver::solve before analyze");
  if (f.rows() != n_ || b.rows() != A_.rows() || b.cols() != f.cols() || (o.initial && o.initial->rows() != n_))
    throw InvalidInput("paper solve: right-hand sides or start do not match the analyzed program");
  // Minimum norm: the paper's A⁺b. Nearest to the start: start + A⁺(b − A·start), the
  // smallest change that satisfies the rows.
  const auto on_touched = [this](const Eigen::MatrixXd& M) {
    Eigen::MatrixXd out(static_cast<Eigen::Index>(touched_.size()), M.cols());
    for (std::size_t k = 0; k < touched_.size(); ++k) out.row(static_cast<Eigen::Index>(k)) = M.row(touched_[k]);
    return out;
  };
  Eigen::MatrixXd fixed;
  if (o.nearest_to_initial && o.initial) {
    fixed = on_touched(*o.initial) + ls_->solve(b - A_ * *o.initial).X;
  } else {
    fixed = ls_->solve(b).X;
  }
  red_.g_free.resize(static_cast<Eigen::Index>(red_.free.size()), f.cols());
  for (std::size_t k = 0; k < red_.free.size(); ++k) red_.g_free.row(static_cast<Eigen::Index>(k)) = f.row(red_.free[k]);
  red_.set_fixed_values(fixed);
  QpReport out;
  Eigen::MatrixXd x = o.initial ? red_.restrict_to_free(*o.initial)
                                : Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(red_.free.size()), f.cols());
  if (red_.free.empty()) {
    out.summary = {Termination::Converged, 0, 0.0, "every unknown is constrained"};
  } else {
    // Callers see the whole n × k iterate. The reduced energy differs from the full one by a
    // constant, the fixed unknowns' own part, so a check costs no product with H (and without
    // a callback nothing is measured).
    const double energy_offset = o.callback ? constrained_energy(f, fixed) : 0.0;
    Eigen::MatrixXd full;
    const IterationCallback expanded = [&](const IterationRecord& r) {
      full = red_.expand(*r.x);
      return o.callback({r.iteration, r.residual, r.seconds, r.energy + energy_offset, &full});
    };
    // A single handle's right-hand side has rank 1: only its independent columns are solved.
    out.summary = solve_independent_columns(free_, red_.A, red_.b, x, o.callback ? expanded : IterationCallback());
  }
  out.p = red_.expand(x);
  out.constraint_residual = std::numeric_limits<double>::quiet_NaN();
  if (o.measure_residual) {  // one product with A serves the residual and the judgement's scale
    const Eigen::MatrixXd Ap = A_ * out.p;  // analyze() refused a program without rows
    out.constraint_residual = (Ap - b).norm();
    if (is_success(out.summary.termination)) judge_rows_met(out, std::max(b.norm(), Ap.norm()));
  }
  return out;
}

void SplitSolver::judge_rows_met(QpReport& out, double scale) const {
  // A⁺b is the rows' least-squares fit: for inconsistent rows (one point pulled to two places)
  // it meets none of them, and the free solve converging says nothing about that. Judged here,
  // on the answer, against a bound far above the factorizations' rounding (1e-12 relative on the
  // bundled edits) and far below any inconsistency a designer would make.
  constexpr double kRowsMetTolerance = 1e-8;
  const double relative = scale > 0 ? out.constraint_residual / scale : out.constraint_residual;
  if (relative <= kRowsMetTolerance) return;
  std::ostringstream msg;
  msg << std::scientific << std::setprecision(2) << "constraints not met: relative residual " << relative << " above "
      << kRowsMetTolerance << " (inconsistent constraint rows: the paper's split fixes their least-squares fit)";
  if (!out.summary.message.empty()) msg << "; " << out.summary.message;
  out.summary.termination = Termination::ConstraintsUnmet;
  out.summary.message = msg.str();
}

}  // namespace fairshape::qp
