// The constrained minimization of §4.3 (Boier-Martin et al.) at one level:
//   minimize ½ Σ_c ΔP_cᵀ H ΔP_c − gᵀΔP   subject to   A ΔP = C.
// `paper`: the constrained vertices' deformations from the minimum-norm least-squares
//          solution of A ΔP_c = C, then fixed; the free ones from the given solver (Gauss-
//          Seidel, SOR, CG, Cholesky) on the reduced system.
// `kkt`, `qr_penalty`, `range_space`: the registered constrained solvers of src/qp (Welch &
//          Witkin §4.3) on the same program — the exact minimizer, for comparison; one
//          dependent-row policy (qp/row_dependence.h).
// Point constraints alone keep x, y and z apart (three right-hand sides of one n × n system);
// normal constraints couple them, and both modes then solve the one 3n × 3n system of §5.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "fairshape/design/constrained_freedom.h"
#include "fairshape/core/backend.h"
#include "fairshape/design/multires_constraints.h"
#include "fairshape/solver/level_operators.h"
#include "fairshape/problem/constrained_system.h"
#include "fairshape/core/config.h"
#include "fairshape/core/name_table.h"
#include "fairshape/solver/solver.h"

namespace fairshape {

// Kkt / QrPenalty / RangeSpace: the qp registry's solver of that name.
enum class ConstraintMode { Paper, Kkt, QrPenalty, RangeSpace };
//! paper | kkt | qr_penalty | range_space, as in problem.constraint_mode.
const NameTable<ConstraintMode>& constraint_mode_names();

struct EditProblem {
  SparseMatrix H;      // n × n, shared by x, y, z
  Eigen::MatrixXd g;   // n × 3 linear term (thin plate: −H P_rest; detail-preserving: 0)
  //! The energy of ΔP = 0: ½ P_restᵀ H P_rest of the terms measured on positions (0 for energies
  //! of the deformation), so energy(ΔP) = ½ΔPᵀHΔP − gᵀΔP + energy_at_rest is the energy of the
  //! result itself and never negative.
  double energy_at_rest = 0;
  LinearConstraints constraints;
  //! The levels below this one, for multilevel solvers (empty: a single-level problem).
  std::shared_ptr<const LevelOperators> levels;
  //! The unknowns are a region of a level whose other vertices are held (design/regional_edit.h):
  //! the energy's coupling to them fixes translations, so no point row is needed.
  bool anchored = false;
};

struct EditSolution {
  Eigen::MatrixXd delta;  // n × 3
  SolveSummary summary;
  double analyze_s = 0, solve_s = 0;  // factorization/setup, then the solve proper
  double constraint_residual = 0;  // ‖A ΔP − C‖_F
  int constrained_vertices = 0;
};

//! \throw InvalidInput when there are no constraints (the deformation is then undetermined
//! for translation-invariant energies) or sizes disagree.
//! `initial` (optional, n × 3) starts the iterative solvers on the free vertices; `cb` gets
//! the full n × 3 deformation as its iterate.
//! `qp_options`: the options of a QP mode's solver (problem.<mode>: {...}).
EditSolution solve_edit(const EditProblem& p, ConstraintMode mode, Solver& free_solver, Backend backend,
                        const IterationCallback& cb = {}, const Eigen::MatrixXd* initial = nullptr, Config qp_options = {});

namespace qp {
class QpSolver;
}

//! How the paper mode sets the constrained vertices: the minimum-norm solution of their rows
//! (§4.3), or the one nearest to the initial guess (a prolongated coarse solution, whose
//! shape the minimum-norm one would replace by a spike on coarse levels).
enum class ConstrainedStart { MinimumNorm, NearestToInitial };

//! solve_edit split where a drag splits it: what depends only on H and the constraint rows
//! (paper: the least-squares factorization of the constrained vertices, the reduced system,
//! the solver's analysis; the QP modes: their solver's analyze()) is done once; then any targets
//! of the same rows are solved. `p` and `solver` must outlive this object.
class PreparedEdit {
 public:
  //! \throw InvalidInput like solve_edit.
  PreparedEdit(const EditProblem& p, ConstraintMode mode, Solver& solver, Backend backend, Config qp_options = {});
  ~PreparedEdit();
  //! C: targets of p.constraints.A (m × 3); normal constraints keep their own. The QP modes
  //! are direct: they ignore `cb` and `initial`.
  EditSolution solve(const Eigen::MatrixXd& C, const IterationCallback& cb = {}, const Eigen::MatrixXd* initial = nullptr,
                     ConstrainedStart constrained = ConstrainedStart::MinimumNorm);
  //! solve(), then (paper mode) the constrained unknowns' remaining freedom optimized too: the
  //! problem's minimizer, not the split's answer (design/constrained_freedom.h). Each free
  //! direction d of the constrained unknowns is followed by the free ones (one more split solve
  //! of the homogeneous problem each), and the energy minimized over their span exactly (a d × d
  //! system). Up to kMaxFreedom directions; beyond, the split's answer with a note.
  EditSolution solve_to_optimum(const Eigen::MatrixXd& C, const IterationCallback& cb = {},
                                const Eigen::MatrixXd* initial = nullptr);
  static constexpr int kMaxFreedom = 256;
  double analyze_s() const { return analyze_s_; }
  //! Replaces the problem's linear term g (n × 3) for the next solves: a rotation-aware edit
  //! changes only g between its iterations, so the analysis is kept.
  void set_linear_term(const Eigen::MatrixXd& g);
  //! ‖A ΔP − C‖ for a result of solve(). solve() measures it itself unless told not to: a
  //! cascade's intermediate levels throw it away, and on a coarse level under a fine fixed
  //! region it is a product with hundreds of thousands of propagated rows (a third of an
  //! interactive step at 1.1M vertices).
  double constraint_residual(const Eigen::MatrixXd& delta, const Eigen::MatrixXd& C) const;
  void measure_constraints(bool measure) { measure_constraints_ = measure; }

 private:
  const EditProblem& solved() const { return stacked_ ? *stacked_ : *original_; }
  const EditProblem* original_ = nullptr;
  std::optional<EditProblem> stacked_;  // the coupled 3n system when there are normal constraints
  std::optional<Eigen::MatrixXd> g_;    // set_linear_term's, in the solved system's layout
  std::unique_ptr<qp::QpSolver> qp_;    // every mode: src/qp's solver (paper: the split)
  bool paper_ = false;
  int constrained_vertices_ = 0;  // unknowns some constraint row reaches
  double analyze_s_ = 0;
  bool measure_constraints_ = true;
  std::optional<ConstrainedFreedom> freedom_;  // solve_to_optimum's, found on first use
};

//! The energy of an edit's result (configs/README.md, "energy"): the energy terms of the
//! deformation ΔP, or of P_rest + ΔP for terms measured on positions. Never negative.
double edit_energy(const EditProblem& p, const Eigen::MatrixXd& delta);

//! [C stacked by coordinate; the coupled targets]: the right-hand side of the coupled system.
Eigen::MatrixXd stacked_targets(const LinearConstraints& lc, const Eigen::MatrixXd& C);

//! `rest` with level `level` moved by `delta` and the finer levels synthesized from it, their
//! local details kept (§3): the surface an edit-level answer stands for.
MultiresSurface with_deformation(const MultiresSurface& rest, int level, const Eigen::MatrixXd& delta);

}  // namespace fairshape
