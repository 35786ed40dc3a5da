// A range-space solver of the KKT system with CHOLMOD, the peer the Lagrange and penalty
// solvers are measured against, and the one whose factor can be updated in place:
//   H_ρ = H + ρ AᵀA  (same minimizer on {A p = b}; positive definite once A pins H's null space),
//   S = A H_ρ⁻¹ Aᵀ   (m × m, dense: constraint counts are small next to n),
//   λ = S⁺ (A H_ρ⁻¹ g − b),  p = H_ρ⁻¹ (g − Aᵀλ),  g = f + ρ Aᵀ b.
// Adding constraint rows C borders S (H_ρ is already positive definite, so C need not enter
// it: one solve per new row and a re-decomposition of the small S); removing rows that are part
// of H_ρ is the downdate H_ρ − ρ CᵀC by cholmod_updown on the simplicial LDLᵀ factor, then S is
// rebuilt; neither refactors H_ρ. Dependent rows leave S singular; its eigendecomposition over the
// rank of the unit rows (minimum-norm λ) takes care of them, so nothing needs dropping.
#pragma once

#include <Eigen/QR>

#include <memory>
#include <optional>
#include <vector>

#include "fairshape/qp/constraint_policy.h"
#include "fairshape/qp/qp_solver.h"

namespace fairshape::qp {

class RangeSpaceSolver final : public QpSolver {
 public:
  explicit RangeSpaceSolver(ConstraintPolicy policy = {});
  ~RangeSpaceSolver() override;
  void analyze(const QuadraticProgram& qp) override;
  QpReport solve(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b) override;

  //! analyze() of a program with the same H as the last one and rows that mostly agree with
  //! the current ones (a design step that adds or removes constraints) updates the factor:
  //! the rows no longer there are removed, the new ones added; b then comes in the program's
  //! own row order. The last analyze's update (rows added, removed), or none: refactored.
  struct RowUpdate {
    int added = 0, removed = 0;
  };
  const std::optional<RowUpdate>& last_update() const { return last_update_; }

  //! Appends constraint rows (their targets come with the next solve's b). \throw InvalidInput
  //! when the column count differs.
  void add_rows(const SparseMatrix& rows);
  //! Removes the given rows (indices into the current A).
  void remove_rows(std::vector<int> rows);
  //! S and H_ρ⁻¹Aᵀ are dense: beyond this many rows the other solvers are the right tools.
  static constexpr int kMaxRows = 3000;

 private:
  bool update_rows(const SparseMatrix& A);
  bool factor_positive_definite() const;
  void updown(bool update, const SparseMatrix& rows);
  void rebuild_schur();
  void decompose_schur();  // S's decomposition and condition estimate
  Eigen::MatrixXd solve_h(const Eigen::MatrixXd& rhs) const;

  struct Cholmod;
  std::unique_ptr<Cholmod> chol_;
  ConstraintPolicy policy_;
  SparseMatrix H_, A_;  // A_: the unit-norm rows of A_original_ (scaling_.d)
  SparseMatrix A_original_;
  RowScaling scaling_;
  double rho_ = 1;
  Eigen::MatrixXd Z_;  // H_ρ⁻¹ Aᵀ
  Eigen::MatrixXd S_;
  ConstraintConditioning conditioning_;  // S over the independent directions: minimum-norm multipliers
  bool singular_ = false;
  std::optional<RowUpdate> last_update_;
  std::vector<int> order_;  // after an update: solver row i is row order_[i] of the program; empty: the same
  std::vector<char> in_factor_;  // per row of A: part of H_ρ (analyze) or bordered on (add_rows)
};

//! How `solver`'s last analyze() got its factor, for reports (steps.csv's `factorization`): the
//! range-space solver updates it across design steps that only add or remove constraints,
//! "updated (+a -r rows)"; KKT and QR-penalty keep theirs while H and A are unchanged,
//! "reused"; otherwise "factored".
std::string factorization_note(const QpSolver& solver);

}  // namespace fairshape::qp
