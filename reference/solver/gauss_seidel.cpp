// Reference `gauss_seidel` and `sor`: lexicographic sweeps, straight from the textbook
//   x_i ← (1 − ω) x_i + ω (b_i − Σ_{j≠i} a_ij x_j) / a_ii,   i = 0, 1, …, n − 1.
#include "problem/constrained_system.h"
#include "solver/iterative.h"

namespace fairshape::reference {
namespace {

class LexicographicSor : public Solver {
 public:
  LexicographicSor(IterativeOptions opt, double omega) : opt_(opt), omega_(omega) {}
  void analyze(const SparseMatrix& A) override { A_ = A; }

  SolveSummary solve(const SparseMatrix& A, const Eigen::MatrixXd& b, Eigen::MatrixXd& x,
                     const IterationCallback& cb) override {
    if (A_.rows() != A.rows()) analyze(A);
    IterationMonitor monitor(opt_, cb, system_energy(A, b));
    const Eigen::VectorXd diag = A.diagonal();
    if (const auto problem = diagonal_problem(diag); !problem.empty()) {
      monitor.fail(problem);
      return monitor.summary();
    }
    if (!monitor.record(0, relative_residual(A, b, x), x)) return monitor.summary();
    for (int it = 1;; ++it) {
      for (Eigen::Index i = 0; i < A_.rows(); ++i) {
        Eigen::RowVectorXd sigma = Eigen::RowVectorXd::Zero(x.cols());
        for (RowSparseMatrix::InnerIterator e(A_, i); e; ++e)
          if (e.col() != i) sigma += e.value() * x.row(e.col());
        x.row(i) = (1 - omega_) * x.row(i) + omega_ * (b.row(i) - sigma) / diag[i];
      }
      if (monitor.should_check(it) && !monitor.record(it, relative_residual(A, b, x), x)) break;
    }
    return monitor.summary();
  }

 private:
  IterativeOptions opt_;
  double omega_;
  RowSparseMatrix A_;
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
