// The petsc_* solvers (the multigrid's peers, and its distributed back end): conjugate gradients
// preconditioned by PETSc's PCMG over fairshape's own prolongations (petsc_mg), PETSc's GAMG
// (petsc_gamg) or hypre's BoomerAMG (petsc_boomeramg). One implementation serves both back-end
// names: PETSc is the external peer the optimized and reference solvers are measured against.
// petsc.ranks = 1 solves in this process on one rank (a singleton MPI process); more ranks hand
// the system to an MPI job (petsc_distributed.h). Either way the answer is judged here: the
// residual in the summary is ‖b − A x‖ / ‖b‖ recomputed from A, not PETSc's own report.
#include <Eigen/QR>

#include <cstdio>
#include <memory>

#include "fairshape/core/error.h"
#include "fairshape/core/timer.h"
#include "fairshape/problem/constrained_system.h"
#include "fairshape/solver/level_operators.h"
#include "fairshape/solver/matrix_fingerprint.h"
#include "fairshape/solver/multigrid.h"
#include "fairshape/solver/petsc_distributed.h"
#include "fairshape/solver/petsc_ksp.h"
#include "fairshape/solver/petsc_runtime.h"
#include "fairshape/solver/solver.h"

namespace fairshape {
namespace {

using petsc::Preconditioner;
using petsc::Settings;

// The columns' outcomes as one: the first failure, else the first column's success kind.
void combine(SolveSummary& total, const SolveSummary& column, bool first) {
  if (first || (total.succeeded() && !column.succeeded())) {
    total.termination = column.termination;
    if (!column.message.empty()) total.message = column.message;
  }
  total.iterations = std::max(total.iterations, column.iterations);
  total.error_estimate = std::max(total.error_estimate, column.error_estimate);  // the worst column's
  total.observe_s += column.observe_s;
}

class PetscSolver : public Solver {
 public:
  explicit PetscSolver(Settings s) : s_(std::move(s)) {}

  bool uses_levels() const override {
    return s_.preconditioner == Preconditioner::Mg || (s_.preconditioner == Preconditioner::Gamg && s_.linear_near_null_space);
  }
  void set_levels(std::shared_ptr<const LevelOperators> ops, const LevelSelection& selection) override {
    ops_ = std::move(ops);
    selection_ = selection;
    forget();
  }

  void analyze(const SparseMatrix& A) override {
    if (!s_.refusals.empty()) throw InvalidConfig(s_.refusals.front());
    forget();
    const Timer timer;
    non_positive_row_ = first_non_positive_diagonal(A);
    if (non_positive_row_ >= 0) {  // not SPD: solve() says so (PETSc's CG does not always notice)
      analyzed_.remember(A);
      return;
    }
    prolongations_ = prolongations(A);
    near_null_ = near_null_space(A);
    if (s_.ranks == 1) set_up_here(A);
    setup_s_ = timer.seconds();
    analyzed_.remember(A);
  }

  SolveSummary solve(const SparseMatrix& A, const Eigen::MatrixXd& b, Eigen::MatrixXd& x, const IterationCallback& cb) override {
    if (!analyzed_.is(A)) analyze(A);
    if (non_positive_row_ >= 0) {
      SolveSummary s;
      s.termination = Termination::NumericalFailure;
      s.message = s_.solver_name() + ": the matrix is not positive definite (diagonal entry " +
                  std::to_string(non_positive_row_) + " is not positive); conjugate gradients need an SPD system";
      s.residual = relative_residual(A, b, x);
      return s;
    }
    SolveSummary s = s_.ranks == 1 ? solve_here(A, b, x, cb) : solve_on_ranks(A, b, x, cb);
    s.residual = relative_residual(A, b, x);
    if (!x.allFinite()) {
      s.termination = Termination::NumericalFailure;
      s.message = s_.solver_name() + " produced non-finite values";
    } else if (s.termination == Termination::Converged && s_.iterative.tolerance > 0 && s.residual > 2 * s_.iterative.tolerance) {
      // PETSc's recursive residual drifts from the true one (measured: 6.3e-10 true at rtol 1e-10 on
      // 2 ranks, level 5): the true one decides, with a factor 2 for rounding.
      s.termination = Termination::NumericalFailure;
      char text[96];
      std::snprintf(text, sizeof text, "%.3g, above the tolerance %.3g", s.residual, s_.iterative.tolerance);
      s.message = s_.solver_name() + ": PETSc reported convergence, but the true relative residual is " + text +
                  " (its recursive residual drifted)";
    }
    return s;
  }

 private:
  void forget() {
    analyzed_.forget();
    non_positive_row_ = -1;
    ksp_.reset();
    here_P_.clear();
    here_null_.clear();
    here_A_.reset();
  }

  static Eigen::Index first_non_positive_diagonal(const SparseMatrix& A) {
    const Eigen::VectorXd d = A.diagonal();
    for (Eigen::Index i = 0; i < d.size(); ++i)
      if (!(d[i] > 0)) return i;
    return -1;
  }

  // fairshape's prolongations restricted to the kept unknowns ([l] maps level l − 1 to l), the
  // coarse operators left to PETSc (Galerkin, PCMG's MatPtAP).
  std::vector<SparseMatrix> prolongations(const SparseMatrix& A) const {
    if (s_.preconditioner != Preconditioner::Mg) return {};
    if (!ops_)
      throw InvalidInput("petsc_mg: no hierarchy was given (the problem has no levels below the solve level)");
    MultigridOptions mg;
    mg.coarse_space = s_.coarse_space;
    mg.max_levels = s_.max_levels;
    mg.patch_smoothing = false;
    const GalerkinProduct none = [](const SparseMatrix&, const SparseMatrix& P) { return SparseMatrix(P.cols(), P.cols()); };
    MultigridLevels levels = build_multigrid_levels(A, *ops_, selection_, mg, none);
    std::vector<SparseMatrix> out(levels.size());
    for (std::size_t l = 1; l < levels.size(); ++l) out[l] = std::move(levels[l].P);
    return out;
  }

  // Constants and, with positions, the coordinates' linear functions, per coordinate block,
  // restricted to the kept unknowns and orthonormalized (MatNullSpaceCreate's requirement).
  Eigen::MatrixXd near_null_space(const SparseMatrix& A) const {
    if (s_.preconditioner != Preconditioner::Gamg) return {};
    if (s_.linear_near_null_space && (!ops_ || ops_->positions.rows() == 0))
      throw InvalidInput("petsc_gamg: near_null_space linear needs the vertex positions of a hierarchy (edit a level >= 1), "
                         "or set petsc.near_null_space: constant");
    const int blocks = std::max(selection_.blocks, 1);
    const Eigen::Index n = s_.linear_near_null_space ? ops_->positions.rows() : A.rows() / blocks;
    std::vector<int> kept = selection_.kept;
    if (kept.empty())
      for (Eigen::Index i = 0; i < A.rows(); ++i) kept.push_back(static_cast<int>(i));
    if (static_cast<Eigen::Index>(kept.size()) != A.rows() || n * blocks < A.rows())
      throw InvalidInput("petsc_gamg: the system has " + std::to_string(A.rows()) + " unknowns, the hierarchy's kept set " +
                         std::to_string(kept.size()));
    const int per_block = s_.linear_near_null_space ? 4 : 1;
    Eigen::MatrixXd V = Eigen::MatrixXd::Zero(A.rows(), per_block * blocks);
    for (Eigen::Index i = 0; i < A.rows(); ++i) {
      const Eigen::Index block = kept[static_cast<std::size_t>(i)] / n, vertex = kept[static_cast<std::size_t>(i)] % n;
      V(i, per_block * block) = 1.0;
      if (s_.linear_near_null_space)
        for (int d = 0; d < 3; ++d) V(i, per_block * block + 1 + d) = ops_->positions(vertex, d);
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(V);
    const Eigen::Index rank = qr.rank();  // a planar region's third coordinate is a constant
    return Eigen::MatrixXd(qr.householderQ() * Eigen::MatrixXd::Identity(A.rows(), rank));
  }

  void set_up_here(const SparseMatrix& A) {
    here_A_ = petsc::to_petsc(A);
    std::vector<Mat> interpolations(prolongations_.size(), nullptr);
    for (std::size_t l = 1; l < prolongations_.size(); ++l) {
      here_P_.push_back(petsc::to_petsc(prolongations_[l]));
      interpolations[l] = here_P_.back().get();
    }
    std::vector<Vec> near_null;
    for (Eigen::Index k = 0; k < near_null_.cols(); ++k) {
      here_null_.push_back(petsc::to_petsc(near_null_, k));
      near_null.push_back(here_null_.back().get());
    }
    ksp_ = std::make_unique<petsc::ConfiguredKsp>(PETSC_COMM_SELF, s_, here_A_.get(), interpolations, near_null);
  }

  SolveSummary solve_here(const SparseMatrix& A, const Eigen::MatrixXd& b, Eigen::MatrixXd& x, const IterationCallback& cb) {
    const SystemEnergy energy = system_energy(A, b);
    SolveSummary total;
    std::string per_column;
    int offset = 0;  // a callback sees the columns' iterations one after another
    for (Eigen::Index c = 0; c < b.cols(); ++c) {
      IterationCallback shifted;
      if (cb)
        shifted = [&](const IterationRecord& r) {
          IterationRecord moved = r;
          moved.iteration += offset;
          return cb(moved);
        };
      IterationMonitor monitor(s_.iterative, shifted, energy, /*krylov=*/true);
      petsc::VecHandle bv = petsc::to_petsc(b, c), xv = petsc::to_petsc(x, c);
      const bool warm = !x.col(c).isZero(0.0);
      FS_PETSC(KSPSetInitialGuessNonzero(ksp_->get(), warm ? PETSC_TRUE : PETSC_FALSE));
      std::unique_ptr<petsc::IterateErrorEstimate> estimate;
      if (monitor.estimates_error())
        estimate = std::make_unique<petsc::IterateErrorEstimate>(here_A_.get(), s_.iterative.error_delay);
      petsc::MonitoredTest test{&monitor, &x, c, b.col(c).norm() > 0 ? b.col(c).norm() : 1.0, estimate.get(), nullptr};
      FS_PETSC(KSPSetConvergenceTest(ksp_->get(), petsc::MonitoredTest::test, &test, nullptr));
      FS_PETSC(KSPSolve(ksp_->get(), bv.get(), xv.get()));
      if (test.error) std::rethrow_exception(test.error);
      petsc::copy_to_column(xv.get(), x, c);
      KSPConvergedReason reason;
      FS_PETSC(KSPGetConvergedReason(ksp_->get(), &reason));
      SolveSummary column = monitor.summary();
      // A breakdown (an indefinite preconditioner, NaN) ends PETSc's iteration before fairshape's
      // rules decide: the monitor would call it an iteration cap.
      if (reason < 0 && reason != KSP_DIVERGED_ITS) {
        column.termination = Termination::NumericalFailure;
        column.message = "PETSc: " + petsc::ConfiguredKsp::reason_name(reason);
      }
      combine(total, column, c == 0);
      offset += column.iterations;
      per_column += (c ? ", " : "") + std::to_string(column.iterations);
    }
    total.message = s_.solver_name() + ": CG iterations per column " + per_column + "; set-up " + format_seconds(setup_s_) +
                    (total.message.empty() ? "" : "; " + total.message);
    return total;
  }

  SolveSummary solve_on_ranks(const SparseMatrix& A, const Eigen::MatrixXd& b, Eigen::MatrixXd& x, const IterationCallback& cb) {
    const petsc::DistributedOutcome job = petsc::solve_distributed(s_, A, prolongations_, near_null_, b, x);
    SolveSummary total;
    std::string per_column;
    for (std::size_t c = 0; c < job.iterations.size(); ++c) {
      SolveSummary column;
      const std::string& r = job.reasons[c];
      const bool stops = s_.iterative.tolerance > 0 || s_.iterative.error_tolerance > 0;
      column.termination = r.rfind("CONVERGED", 0) == 0 ? (stops ? Termination::Converged : Termination::ScheduleCompleted)
                           : r == "DIVERGED_ITS" ? (stops ? Termination::MaxIterations : Termination::ScheduleCompleted)
                                                 : Termination::NumericalFailure;
      if (column.termination == Termination::NumericalFailure) column.message = "PETSc: " + r;
      if (s_.iterative.error_tolerance > 0) {
        column.error_estimate = job.error_estimates[c];
        char text[200];
        std::snprintf(text, sizeof text,
                      column.termination == Termination::Converged
                          ? "relative A-norm error estimate %.3g <= %.3g (Hestenes-Stiefel from the iterates, %d iterations late)"
                          : "the iteration cap came before the error tolerance: error estimate %.3g, asked %.3g (delay %d)",
                      column.error_estimate, s_.iterative.error_tolerance, s_.iterative.error_delay);
        if (column.termination != Termination::NumericalFailure) column.message = text;
      }
      column.iterations = job.iterations[c];
      combine(total, column, c == 0);
      per_column += (c ? ", " : "") + std::to_string(job.iterations[c]);
    }
    double peak = 0;
    for (const auto& rank : job.ranks) peak = std::max(peak, rank.max_rss_mb);
    total.message = s_.solver_name() + " on " + std::to_string(s_.ranks) + " MPI ranks: CG iterations per column " + per_column +
                    "; in the job set-up " + format_seconds(job.setup_s) + ", solve " + format_seconds(job.solve_s) +
                    ", whole job " + format_seconds(job.wall_s) + "; peak memory per rank " +
                    std::to_string(static_cast<int>(peak)) + " MB" + (total.message.empty() ? "" : "; " + total.message);
    // The job reports no iterates: a listener sees the answer once, as the last iteration.
    if (cb) cb({total.iterations, relative_residual(A, b, x), job.wall_s, system_energy(A, b)(x), &x});
    return total;
  }

  static std::string format_seconds(double s) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g s", s);
    return text;
  }

  Settings s_;
  std::shared_ptr<const LevelOperators> ops_;
  LevelSelection selection_;
  AnalyzedMatrix analyzed_;
  Eigen::Index non_positive_row_ = -1;
  std::vector<SparseMatrix> prolongations_;
  Eigen::MatrixXd near_null_;
  double setup_s_ = 0;
  // ranks = 1: the system as PETSc objects, kept between solves with the same matrix
  petsc::MatHandle here_A_;
  std::vector<petsc::MatHandle> here_P_;
  std::vector<petsc::VecHandle> here_null_;
  std::unique_ptr<petsc::ConfiguredKsp> ksp_;
};

}  // namespace

std::unique_ptr<Solver> make_petsc_solver(Config& cfg, Preconditioner preconditioner) {
  return std::make_unique<PetscSolver>(Settings::from_config(cfg, preconditioner));
}

}  // namespace fairshape
