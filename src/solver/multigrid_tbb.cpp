// Optimized `multigrid` and `multigrid_cg`: the shared cycle (multigrid.h) over TBB kernels —
// multicolour smoothing, row-parallel residuals and transfers on row-major blocks, the
// Galerkin product gathered in parallel, CHOLMOD on the coarsest level.
#include <Eigen/CholmodSupport>

#include "solver/multigrid.h"
#include "solver/parallel_kernels.h"

namespace fairshape {
namespace {

class ParallelKernels {
 public:
  using Block = RowBlock;

  void setup(const MultigridLevels& levels, double omega) {
    omega_ = omega;
    const std::size_t n = levels.size();
    A_.resize(n);
    P_.assign(n, {});
    PT_.assign(n, {});
    smoothers_.assign(n, {});
    patches_.assign(n, {});
    for (std::size_t l = 0; l < n; ++l) {
      A_[l] = levels[l].A;
      A_[l].makeCompressed();
      if (l > 0) {
        P_[l] = levels[l].P;
        PT_[l] = RowSparseMatrix(levels[l].P.transpose());
        smoothers_[l].analyze(A_[l]);
        patches_[l].setup(levels[l].A, levels[l].patches);
      }
    }
    coarse_A_ = levels[0].A;
    coarse_.compute(coarse_A_);
  }


  int levels() const { return static_cast<int>(A_.size()); }
  Block zeros(int l, Eigen::Index cols) const { return Block::Zero(A_[l].rows(), cols); }
  void smooth(int l, Block& x, const Block& b, int sweeps, bool forward) const {
    if (!forward) patches_[l].apply(A_[l], x, b, false);
    for (int s = 0; s < sweeps; ++s) smoothers_[l].sweep(A_[l], x, b, omega_, forward);
    if (forward) patches_[l].apply(A_[l], x, b, true);
  }
  Block residual(int l, const Block& x, const Block& b) const {
    Block r;
    parallel_residual(A_[l], x, b, r);
    return r;
  }
  Block multiply(int l, const Block& x) const {
    Block y;
    parallel_multiply(A_[l], x, y);
    return y;
  }
  Block restrict_down(int l, const Block& r) const {
    Block c = zeros(l - 1, r.cols());
    parallel_multiply_add(PT_[l], r, c);
    return c;
  }
  void prolong_add(int l, const Block& e, Block& x) const { parallel_multiply_add(P_[l], e, x); }
  bool coarse_solve(const Block& b, Block& x) {
    if (coarse_.info() != Eigen::Success) return false;
    const Eigen::MatrixXd bc = b;
    x = coarse_.solve(bc);
    return x.allFinite() && coarse_solve_accurate(coarse_A_, bc, Eigen::MatrixXd(x));
  }
  Eigen::VectorXd column_dots(const Block& a, const Block& c) const { return parallel_column_dots(a, c); }
  Block to_block(const Eigen::MatrixXd& m) const { return m; }
  Eigen::MatrixXd from_block(const Block& m) const { return m; }

 private:
  std::vector<RowSparseMatrix> A_, P_, PT_;
  std::vector<MulticolorSmoother> smoothers_;
  std::vector<PatchSmoother> patches_;
  SparseMatrix coarse_A_;
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> coarse_;
  double omega_ = 1.0;
};

}  // namespace

std::unique_ptr<Solver> make_parallel_multigrid(Config& cfg) {
  return make_multigrid_solver<ParallelKernels>(cfg, false, parallel_galerkin_product);
}

std::unique_ptr<Solver> make_parallel_multigrid_cg(Config& cfg) {
  return make_multigrid_solver<ParallelKernels>(cfg, true, parallel_galerkin_product);
}

}  // namespace fairshape
