// Optimized `gauss_seidel` and `sor`: multicolour SOR (parallel_kernels.h), one
// tbb::parallel_for per colour, on a row-major copy of A and a row-major iterate.
// Rows of one colour are independent, so the result does not depend on the thread count.
// The copy and its colouring are redone whenever a solve brings another matrix (solver.h).
#include "fairshape/solver/iterative.h"
#include "fairshape/solver/matrix_fingerprint.h"
#include "fairshape/solver/parallel_kernels.h"

namespace fairshape {
namespace {

class MulticolorSor : public Solver {
 public:
  MulticolorSor(IterativeOptions opt, double omega) : opt_(opt), omega_(omega) {}

  void analyze(const SparseMatrix& A) override {
    A_ = A;
    A_.makeCompressed();
    smoother_.analyze(A_);
    analyzed_.remember(A);
  }

  SolveSummary solve(const SparseMatrix& A, const Eigen::MatrixXd& b, Eigen::MatrixXd& x,
                     const IterationCallback& cb) override {
    if (!analyzed_.is(A)) analyze(A);
    IterationMonitor monitor(opt_, cb, system_energy(A, b));
    if (const auto problem = diagonal_problem(smoother_.diagonal()); !problem.empty()) {
      monitor.fail(problem);
      return monitor.summary();
    }
    RowBlock xr = x, br = b, r;
    const double b_norm = b.norm() > 0 ? b.norm() : 1.0;
    const auto record = [&](int it) {
      parallel_residual(A_, xr, br, r);
      if (monitor.wants_iterate()) monitor.observe([&] { x = xr; });
      return monitor.record(it, std::sqrt(parallel_column_dots(r, r).sum()) / b_norm, x);
    };
    if (!record(0)) return monitor.summary();
    for (int it = 1;; ++it) {
      smoother_.sweep(A_, xr, br, omega_, true);
      if (monitor.should_check(it) && !record(it)) break;
    }
    x = xr;
    return monitor.summary();
  }

 private:
  IterativeOptions opt_;
  double omega_;
  RowSparseMatrix A_;
  MulticolorSmoother smoother_;
  AnalyzedMatrix analyzed_;
};

}  // namespace

std::unique_ptr<Solver> make_multicolor_gauss_seidel(Config& cfg) {
  return std::make_unique<MulticolorSor>(IterativeOptions::from_config(cfg), 1.0);
}

std::unique_ptr<Solver> make_multicolor_sor(Config& cfg) {
  const auto opt = IterativeOptions::from_config(cfg);
  return std::make_unique<MulticolorSor>(opt, sor_omega_from_config(cfg));
}

}  // namespace fairshape
