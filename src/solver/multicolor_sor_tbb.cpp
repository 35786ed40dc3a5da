// Optimized `gauss_seidel` and `sor`: multicolour SOR, one tbb::parallel_for per colour,
// on a row-major copy of A and a row-major iterate (x, y, z of a vertex side by side).
// Rows of one colour are independent, so the result does not depend on the thread count.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/partitioner.h>

#include "solver/graph_coloring.h"
#include "solver/iterative.h"

namespace fairshape {
namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

class MulticolorSor : public Solver {
 public:
  MulticolorSor(IterativeOptions opt, double omega) : opt_(opt), omega_(omega) {}

  void analyze(const SparseMatrix& A) override {
    A_ = A;
    A_.makeCompressed();
    classes_ = color_rows(A_);
    diag_ = A.diagonal();
  }

  SolveSummary solve(const SparseMatrix& A, const Eigen::MatrixXd& b, Eigen::MatrixXd& x,
                     const IterationCallback& cb) override {
    if (A_.rows() != A.rows()) analyze(A);
    IterationMonitor monitor(opt_, cb, system_energy(A, b));
    if (const auto problem = diagonal_problem(diag_); !problem.empty()) {
      monitor.fail(problem);
      return monitor.summary();
    }
    RowMatrix xr = x, br = b;
    const double b_norm = b.norm() > 0 ? b.norm() : 1.0;
    if (!monitor.record(0, residual_norm(xr, br) / b_norm, x)) return monitor.summary();
    for (int it = 1;; ++it) {
      for (const auto& rows : classes_) sweep_color(rows, xr, br);
      if (!monitor.should_check(it)) continue;
      x = xr;
      if (!monitor.record(it, residual_norm(xr, br) / b_norm, x)) break;
    }
    x = xr;
    return monitor.summary();
  }

 private:
  void sweep_color(const std::vector<int>& rows, RowMatrix& x, const RowMatrix& b) const {
    const int cols = static_cast<int>(x.cols());
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, rows.size(), 256),
        [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t k = r.begin(); k != r.end(); ++k) {
            const int i = rows[k];
            double sigma[3] = {0, 0, 0};
            for (RowSparseMatrix::InnerIterator it(A_, i); it; ++it)
              if (it.col() != i)
                for (int c = 0; c < cols; ++c) sigma[c] += it.value() * x(it.col(), c);
            for (int c = 0; c < cols; ++c)
              x(i, c) = (1 - omega_) * x(i, c) + omega_ * (b(i, c) - sigma[c]) / diag_[i];
          }
        },
        tbb::static_partitioner());
  }

  double residual_norm(const RowMatrix& x, const RowMatrix& b) const {
    const double sq = tbb::parallel_deterministic_reduce(
        tbb::blocked_range<Eigen::Index>(0, A_.rows(), 1024), 0.0,
        [&](const tbb::blocked_range<Eigen::Index>& r, double acc) {
          for (Eigen::Index i = r.begin(); i != r.end(); ++i) {
            Eigen::RowVectorXd ri = b.row(i);
            for (RowSparseMatrix::InnerIterator it(A_, i); it; ++it) ri -= it.value() * x.row(it.col());
            acc += ri.squaredNorm();
          }
          return acc;
        },
        std::plus<double>());
    return std::sqrt(sq);
  }

  IterativeOptions opt_;
  double omega_;
  RowSparseMatrix A_;
  Eigen::VectorXd diag_;
  std::vector<std::vector<int>> classes_;
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
