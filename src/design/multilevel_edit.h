// The accuracy ladder of Boier-Martin et al. §5 ("Multigrid optimization", Figure 8): the
// same edit solved on the levels coarse..L of a hierarchy, each with the designer's
// constraints propagated to it (Table 1), trading accuracy for time.
//   interactive: the coarse level solved directly (factored once), the deformation then
//                subdivided to level L with the Catmull-Clark rules (Figure 8b);
//   improved:    the paper's cascade (Figure 8c–f): coarse solve, then on each finer level
//                prolongate and relax a fixed number of Gauss-Seidel/SOR sweeps, the
//                constrained vertices moved by the least change that satisfies that level's
//                rows (the paper's minimum-norm values from zero would replace the
//                prolongated shape by a spike under a fine handle);
//   converged:   the configured solver on level L, to its tolerance, started from the
//                interactive approximation; the constrained unknowns' remaining freedom
//                optimized too (PreparedEdit::solve_to_optimum), so the answer is the
//                problem's minimizer, also under normal constraints.
// A drag is a sequence of solve() calls with the same constraint set and moving targets;
// each step warm-starts from the previous one corrected by the change of the coarse
// solution, prolongated (x₀ = x_prev + P (c − c_prev)), level by level in the cascade.
#pragma once

#include <functional>
#include <memory>
#include <string_view>
#include <vector>

#include "fairshape/design/edit_solve.h"

namespace fairshape {

enum class Accuracy { Interactive, Improved, Converged };
std::string_view to_string(Accuracy a);
//! \throw InvalidInput naming the valid choices.
Accuracy accuracy_from_string(std::string_view s);

//! The edit on levels coarse..L: problems[k] lives on level coarse + k; prolongations[k]
//! maps problems[k]'s vertices to problems[k + 1]'s (S_l).
struct EditLadder {
  std::vector<EditProblem> problems;
  std::vector<SparseMatrix> prolongations;
};

using SolverFactory = std::function<std::unique_ptr<Solver>()>;

class MultilevelEdit {
 public:
  //! `direct` solves the coarse level (`coarse_mode`: kkt, the exact minimizer, or the
  //! paper's minimum-norm constrained vertices), `relaxer` (a fixed sweep count) the
  //! cascade's levels, `finest` the converged mode; all are analyzed here, once per
  //! constraint set.
  //! \throw InvalidInput for an empty ladder or operators that do not chain.
  MultilevelEdit(const EditLadder& ladder, Accuracy accuracy, const SolverFactory& direct, const SolverFactory& relaxer,
                 Solver& finest, Backend backend, ConstraintMode coarse_mode = ConstraintMode::Kkt);
  ~MultilevelEdit();

  //! One design step with every target scaled by `scale` (the handles dragged along their
  //! offsets; 1 = the configured edit). The deformation of level L; summary.iterations
  //! counts the finest level's iterations (converged) or every relaxation sweep (improved).
  EditSolution solve(double scale, const IterationCallback& cb = {});
  //! One design step with the targets C (m × 3) on every level: the rows are propagated from the
  //! same placed constraints, so each level's C holds the same targets in the same order.
  EditSolution solve(const Eigen::MatrixXd& C, const IterationCallback& cb = {});
  //! Replaces every level's linear term g (problems[k]'s layout, n_k × 3) for the next solves
  //! and forgets the previous step, so the next solve starts cold: a regional pass
  //! (design/regional_edit.h) solves for an increment each round, with the energy of the whole
  //! deformation so far as its linear term and its targets written into the ladder's problems.
  void restart_with_linear_terms(const std::vector<Eigen::MatrixXd>& g);
  //! After solve(): the deformation on each level of the ladder (Figure 8 d–f).
  const std::vector<Eigen::MatrixXd>& level_solutions() const { return current_; }
  double analyze_s() const { return analyze_s_; }

 private:
  Eigen::MatrixXd prolongate(std::size_t from_level, std::size_t to_level, const Eigen::MatrixXd& x) const;
  //! `targets(k)`: level k's; the edit level's residual is measured against s × edit_C.
  EditSolution solve_with(const std::function<Eigen::MatrixXd(std::size_t)>& targets, double s,
                          const Eigen::MatrixXd& edit_C, const IterationCallback& cb);

  const EditLadder& ladder_;
  Accuracy accuracy_;
  Backend backend_;
  std::vector<RowSparseMatrix> rows_;  // the prolongations row-major, for the parallel product
  RowSparseMatrix edit_rows_;          // the edit level's constraint rows, row-major (optimized interactive mode)
  std::vector<std::unique_ptr<Solver>> solvers_;
  std::vector<std::unique_ptr<PreparedEdit>> prepared_;  // per level; only those the mode needs
  std::vector<Eigen::MatrixXd> current_, previous_;
  double analyze_s_ = 0;
};

}  // namespace fairshape
