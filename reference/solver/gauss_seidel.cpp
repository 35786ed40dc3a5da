// Reference `gauss_seidel` and `sor`: lexicographic sweeps (lexicographic_sweep.h) over a
// row-major copy of A, made again whenever a solve brings another matrix (solver.h).
#include "fairshape/problem/constrained_system.h"
#include "fairshape/reference/solver/lexicographic_sweep.h"
#include "fairshape/solver/iterative.h"
#include "fairshape/solver/matrix_fingerprint.h"

namespace fairshape::reference {
namespace {

class LexicographicSor : public Solver {
 public:
  LexicographicSor(IterativeOptions opt, double omega) : opt_(opt), omega_(omega) {}
  void analyze(const SparseMatrix& A) override {
    A_ = A;
    analyzed_.remember(A);
  }

  SolveSummary solve(const SparseMatrix& A, const Eigen::MatrixXd& b, Eigen::MatrixXd& x,
                     const IterationCallback& cb) override {
    if (!analyzed_.is(A)) analyze(A);
    IterationMonitor monitor(opt_, cb, system_energy(A, b));
    const Eigen::VectorXd diag = A.diagonal();
    if (const auto problem = diagonal_problem(diag); !problem.empty()) {
      monitor.fail(problem);
      return monitor.summary();
    }
    if (!monitor.record(0, relative_residual(A, b, x), x)) return monitor.summary();
    for (int it = 1;; ++it) {
      lexicographic_sweep(A_, diag, x, b, omega_);
      if (monitor.should_check(it) && !monitor.record(it, relative_residual(A, b, x), x)) break;
    }
    return monitor.summary();
  }

 private:
  IterativeOptions opt_;
  double omega_;
  RowSparseMatrix A_;
  AnalyzedMatrix analyzed_;
};

}  // namespace

std::unique_ptr<Solver> make_gauss_seidel(Config& cfg) {
  return std::make_unique<LexicographicSor>(IterativeOptions::from_config(cfg), 1.0);
}

std::unique_ptr<Solver> make_sor(Config& cfg) {
  const auto opt = IterativeOptions::from_config(cfg);
  return std::make_unique<LexicographicSor>(opt, sor_omega_from_config(cfg));
}

}  // namespace fairshape::reference
