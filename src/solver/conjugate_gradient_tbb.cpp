// Optimized `conjugate_gradient`: the shared CG algorithm with a TBB row-parallel product on a
// row-major copy of A, made again whenever a solve brings another matrix (solver.h).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "fairshape/solver/conjugate_gradient.h"
#include "fairshape/solver/matrix_fingerprint.h"

namespace fairshape {
namespace {

class ParallelCg : public Solver {
 public:
  explicit ParallelCg(IterativeOptions opt) : opt_(opt) {}
  void analyze(const SparseMatrix& A) override {
    A_ = A;
    A_.makeCompressed();
    diag_ = A.diagonal();
    analyzed_.remember(A);
  }
  SolveSummary solve(const SparseMatrix& A, const Eigen::MatrixXd& b, Eigen::MatrixXd& x,
                     const IterationCallback& cb) override {
    if (!analyzed_.is(A)) analyze(A);
    auto multiply = [this](const Eigen::MatrixXd& p) {
      Eigen::MatrixXd out(p.rows(), p.cols());
      tbb::parallel_for(
          tbb::blocked_range<Eigen::Index>(0, A_.rows(), 1024),
          [&](const tbb::blocked_range<Eigen::Index>& r) {
            for (Eigen::Index i = r.begin(); i != r.end(); ++i) {
              for (Eigen::Index c = 0; c < p.cols(); ++c) {
                double s = 0;
                for (RowSparseMatrix::InnerIterator it(A_, i); it; ++it) s += it.value() * p(it.col(), c);
                out(i, c) = s;
              }
            }
          },
          tbb::static_partitioner());
      return out;
    };
    return conjugate_gradient(multiply, diag_, b, x, opt_, cb);
  }

 private:
  IterativeOptions opt_;
  RowSparseMatrix A_;
  Eigen::VectorXd diag_;
  AnalyzedMatrix analyzed_;
};

}  // namespace

std::unique_ptr<Solver> make_parallel_cg(Config& cfg) {
  return std::make_unique<ParallelCg>(IterativeOptions::from_config(cfg));
}

}  // namespace fairshape
