#include "fairshape/design/multilevel_edit.h"

#include "fairshape/core/error.h"
#include "fairshape/core/timer.h"
#include "fairshape/solver/parallel_kernels.h"

namespace fairshape {

std::string_view to_string(Accuracy a) {
  switch (a) {
    case Accuracy::Interactive: return "interactive";
    case Accuracy::Improved: return "improved";
    case Accuracy::Converged: return "converged";
  }
  return "?";
}

Accuracy accuracy_from_string(std::string_view s) {
  for (Accuracy a : {Accuracy::Interactive, Accuracy::Improved, Accuracy::Converged})
    if (s == to_string(a)) return a;
  throw InvalidInput("accuracy '" + std::string(s) + "' is not one of interactive, improved, converged");
}

MultilevelEdit::MultilevelEdit(const EditLadder& ladder, Accuracy accuracy, const SolverFactory& direct,
                               const SolverFactory& relaxer, Solver& finest, Backend backend, ConstraintMode coarse_mode)
    : ladder_(ladder), accuracy_(accuracy), backend_(backend) {
  require_backend(backend);
  Timer setup;
  const std::size_t levels = ladder.problems.size();
  if (levels == 0) throw InvalidInput("multilevel edit: no level to solve on");
  if (ladder.prolongations.size() + 1 != levels)
    throw InvalidInput("multilevel edit: " + std::to_string(levels) + " levels need " + std::to_string(levels - 1) +
                       " prolongations, got " + std::to_string(ladder.prolongations.size()));
  for (std::size_t k = 0; k + 1 < levels; ++k) {
    const SparseMatrix& S = ladder.prolongations[k];
    if (S.cols() != ladder.problems[k].H.rows() || S.rows() != ladder.problems[k + 1].H.rows())
      throw InvalidInput("multilevel edit: prolongation " + std::to_string(k) + " does not map level " +
                         std::to_string(k) + " to level " + std::to_string(k + 1));
    rows_.emplace_back(S);
  }
  if (accuracy == Accuracy::Interactive && backend != Backend::Reference)  // its residual's rows
    edit_rows_ = RowSparseMatrix(ladder.problems.back().constraints.A);
  prepared_.resize(levels);
  const auto prepare = [&](std::size_t k, std::unique_ptr<Solver> s, ConstraintMode mode) {
    solvers_.push_back(std::move(s));
    prepared_[k] = std::make_unique<PreparedEdit>(ladder.problems[k], mode, *solvers_.back(), backend);
  };
  prepare(0, direct(), coarse_mode);
  if (accuracy == Accuracy::Improved)
    for (std::size_t k = 1; k < levels; ++k) prepare(k, relaxer(), ConstraintMode::Paper);
  if (accuracy == Accuracy::Converged && levels > 1)
    prepared_.back() = std::make_unique<PreparedEdit>(ladder.problems.back(), ConstraintMode::Paper, finest, backend);
  // Only the edit level's constraint residual is reported (the interactive mode measures it
  // after subdividing): the coarser levels skip theirs.
  for (std::size_t k = 0; k + 1 < levels; ++k)
    if (prepared_[k]) prepared_[k]->measure_constraints(false);
  current_.resize(levels);
  analyze_s_ = setup.seconds();
}

MultilevelEdit::~MultilevelEdit() = default;

void MultilevelEdit::restart_with_linear_terms(const std::vector<Eigen::MatrixXd>& g) {
  if (g.size() != ladder_.problems.size())
    throw InvalidInput("multilevel edit: " + std::to_string(g.size()) + " linear terms for " +
                       std::to_string(ladder_.problems.size()) + " levels");
  for (std::size_t k = 0; k < g.size(); ++k)
    if (prepared_[k]) prepared_[k]->set_linear_term(g[k]);
  previous_.clear();
}

Eigen::MatrixXd MultilevelEdit::prolongate(std::size_t from, std::size_t to, const Eigen::MatrixXd& x) const {
#if FAIRSHAPE_WITH_TBB
  if (backend_ == Backend::Optimized) {
    RowBlock y = x, next;
    for (std::size_t k = from; k < to; ++k) {
      next.resize(rows_[k].rows(), y.cols());
      parallel_multiply(rows_[k], y, next);
      std::swap(y, next);
    }
    return y;
  }
#endif
  Eigen::MatrixXd y = x;
  for (std::size_t k = from; k < to; ++k) y = ladder_.prolongations[k] * y;
  return y;
}

EditSolution MultilevelEdit::solve(double scale, const IterationCallback& cb) {
  const auto targets = [&](std::size_t k) { return Eigen::MatrixXd(scale * ladder_.problems[k].constraints.C); };
  return solve_with(targets, scale, ladder_.problems.back().constraints.C, cb);
}

EditSolution MultilevelEdit::solve(const Eigen::MatrixXd& C, const IterationCallback& cb) {
  for (const EditProblem& p : ladder_.problems)
    if (C.rows() != p.constraints.C.rows() || C.cols() != p.constraints.C.cols())
      throw InvalidInput("multilevel edit: " + std::to_string(C.rows()) + " targets for " +
                         std::to_string(p.constraints.C.rows()) + " constraint rows");
  return solve_with([&C](std::size_t) { return C; }, 1.0, C, cb);
}

EditSolution MultilevelEdit::solve_with(const std::function<Eigen::MatrixXd(std::size_t)>& targets, double s,
                                        const Eigen::MatrixXd& edit_C, const IterationCallback& cb) {
  Timer step;
  const std::size_t last = ladder_.problems.size() - 1;
  const bool warm = !previous_.empty();
  // The start on level `to`: the previous step's solution there plus the prolongated change
  // of level `from`'s solution (nested iteration for the first step).
  const auto start = [&](std::size_t from, std::size_t to) {
    if (!warm) return prolongate(from, to, current_[from]);
    return Eigen::MatrixXd(previous_[to] + prolongate(from, to, current_[from] - previous_[from]));
  };
  EditSolution out = prepared_[0]->solve(targets(0), last == 0 ? cb : IterationCallback());
  current_[0] = out.delta;
  if (out.summary.termination == Termination::NumericalFailure) {  // nothing to build on
    out.summary.message = "coarse level: " + out.summary.message;
    out.constraint_residual = prepared_[0]->constraint_residual(out.delta, targets(0));
    return out;
  }
  int iterations = 0;
  if (last > 0) {
    switch (accuracy_) {
      case Accuracy::Interactive:
        out.delta = prolongate(0, last, current_[0]);
        out.summary = {Termination::ScheduleCompleted, 0, -1, "interactive: coarse solve subdivided to the edit level"};
#if FAIRSHAPE_WITH_TBB
        out.constraint_residual =
            backend_ == Backend::Reference
                ? (ladder_.problems[last].constraints.A * out.delta - targets(last)).norm()
                : parallel_residual_norm(edit_rows_, out.delta, s, edit_C);
#else
        out.constraint_residual = (ladder_.problems[last].constraints.A * out.delta - targets(last)).norm();
#endif
        break;
      case Accuracy::Improved:
        for (std::size_t k = 1; k <= last; ++k) {
          const Eigen::MatrixXd x0 = start(k - 1, k);
          out = prepared_[k]->solve(targets(k), k == last ? cb : IterationCallback(), &x0, ConstrainedStart::NearestToInitial);
          current_[k] = out.delta;
          iterations += out.summary.iterations;
        }
        out.summary.iterations = iterations;
        break;
      case Accuracy::Converged: {
        const Eigen::MatrixXd x0 = start(0, last);
        // Converged means the problem's minimizer: the constrained unknowns' own freedom (a
        // normal constraint's ring) optimized as well, not frozen where the split puts them.
        out = prepared_[last]->solve_to_optimum(targets(last), cb, &x0);
        break;
      }
    }
    current_[last] = out.delta;
  }
  out.analyze_s = analyze_s_;
  out.solve_s = step.seconds();
  previous_ = current_;
  return out;
}

}  // namespace fairshape
