// Reference `multigrid` and `multigrid_cg`: the shared cycle (multigrid.h) over plain serial
// Eigen — lexicographic Gauss-Seidel/SOR sweeps (forward before, backward after the coarse
// correction), products with P and Pᵀ, Eigen's LDLᵀ on the coarsest level.
#include <Eigen/SparseCholesky>

#include "fairshape/reference/solver/lexicographic_sweep.h"
#include "fairshape/solver/multigrid.h"

namespace fairshape::reference {
namespace {

class SerialKernels {
 public:
  using Block = Eigen::MatrixXd;

  void setup(const SparseMatrix& A, MultigridLevels levels, const MultigridOptions& options) {
    omega_ = options.omega;
    levels_ = std::move(levels);
    levels_.back().A = A;  // the reference keeps its own copy of every level
    rows_.clear();
    diagonals_.clear();
    patches_.assign(levels_.size(), {});
    for (std::size_t l = 0; l < levels_.size(); ++l) {
      rows_.emplace_back(levels_[l].A);
      diagonals_.push_back(levels_[l].A.diagonal());
      patches_[l].setup(rows_[l], levels_[l].patches);
    }
    coarse_.compute(levels_[0].A, options.coarse_space == MultigridOptions::CoarseSpace::Truncated);
  }

  int levels() const { return static_cast<int>(levels_.size()); }
  Block zeros(int l, Eigen::Index cols) const { return Block::Zero(levels_[l].A.rows(), cols); }
  void smooth(int l, Block& x, const Block& b, int sweeps, bool forward) const {
    const RowSparseMatrix& A = rows_[l];
    if (!forward) patches_[l].apply(A, x, b, false);
    for (int s = 0; s < sweeps; ++s) lexicographic_sweep(A, diagonals_[l], x, b, omega_, forward);
    if (forward) patches_[l].apply(A, x, b, true);
  }
  Block residual(int l, const Block& x, const Block& b) const { return b - levels_[l].A * x; }
  Block multiply(int l, const Block& x) const { return levels_[l].A * x; }
  Block restrict_down(int l, const Block& r) const { return levels_[l].P.transpose() * r; }
  void prolong_add(int l, const Block& e, Block& x) const { x += levels_[l].P * e; }
  bool coarse_solve(const Block& b, Block& x) { return coarse_.solve(b, x); }
  Eigen::VectorXd column_dots(const Block& a, const Block& c) const { return a.cwiseProduct(c).colwise().sum().transpose(); }
  Block to_block(const Eigen::MatrixXd& m) const { return m; }
  Eigen::MatrixXd from_block(const Block& m) const { return m; }


 private:
  MultigridLevels levels_;
  std::vector<RowSparseMatrix> rows_;
  std::vector<Eigen::VectorXd> diagonals_;
  std::vector<PatchSmoother> patches_;
  CoarsestSolve<Eigen::SimplicialLDLT<SparseMatrix>> coarse_;
  double omega_ = 1.0;
};

}  // namespace

std::unique_ptr<Solver> make_multigrid(Config& cfg) {
  return make_multigrid_solver<SerialKernels>(cfg, false, serial_galerkin_product);
}

std::unique_ptr<Solver> make_multigrid_cg(Config& cfg) {
  return make_multigrid_solver<SerialKernels>(cfg, true, serial_galerkin_product);
}

}  // namespace fairshape::reference
