// Boier-Martin et al. §4.3's constrained solve as a QpSolver: the unknowns some constraint
// row reaches take the minimum-norm least-squares solution of their rows A p_c = b (or the
// one nearest to a start) and are then fixed; the free unknowns come from a linear solver on
// the reduced system H_ff p_f = f_f − H_fc p_c. This is the paper's answer, not the QP's
// minimizer (kkt gives that): the constrained unknowns are not optimized.
#pragma once

#include <memory>
#include <vector>

#include "fairshape/core/backend.h"
#include "fairshape/problem/constrained_system.h"
#include "fairshape/qp/qp_solver.h"
#include "fairshape/solver/solver.h"

namespace fairshape {
class MinNormLeastSquares;
}

namespace fairshape::qp {

class SplitSolver final : public QpSolver {
 public:
  //! `free_solver` solves the free unknowns; the first form does not own it (it must outlive
  //! this solver). `backend`: the least-squares factorization's.
  SplitSolver(Solver& free_solver, Backend backend);
  SplitSolver(std::unique_ptr<Solver> free_solver, Backend backend);
  ~SplitSolver() override;
  //! \throw InvalidInput without constraint rows, or for a multilevel free solver without levels.
  void analyze(const QuadraticProgram& qp) override;
  QpReport solve(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b) override;
  QpReport solve(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b, const QpSolveOptions& options) override;

 private:
  //! ½ p_cᵀ H_cc p_c − f_cᵀ p_c for the constrained unknowns' values `fixed` (touched_ order).
  double constrained_energy(const Eigen::MatrixXd& f, const Eigen::MatrixXd& fixed) const;
  //! A success whose answer misses its rows (inconsistent rows) becomes constraints_unmet;
  //! `scale`: max(‖b‖, ‖A p‖), what the residual is relative to.
  void judge_rows_met(QpReport& out, double scale) const;

  std::unique_ptr<Solver> owned_;
  Solver& free_;
  Backend backend_;
  Eigen::Index n_ = 0;  // unknowns of the program
  SparseMatrix A_;
  // The full energy is the reduced one plus ½ p_cᵀ H_cc p_c − f_cᵀ p_c (H_cc: H on the
  // constrained unknowns). A program that lends its H (borrowed_H: it outlives the solver) is
  // read through `lent_H_`; an owned one leaves its H_cc here, not a copy of the whole H (H is
  // 1.3 GB at 4.5M unknowns, H_cc a third of it in the cow's Figure 2 edit; at 17.8M unknowns
  // forming H_cc by two sparse products was what ran the level-6 set-up out of memory).
  const SparseMatrix* lent_H_ = nullptr;
  SparseMatrix H_cc_;
  std::vector<int> touched_;
  std::unique_ptr<MinNormLeastSquares> ls_;
  ReducedSystem red_;
};

}  // namespace fairshape::qp
