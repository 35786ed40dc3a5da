// Optimized `multigrid` and `multigrid_cg`: the shared cycle (multigrid.h) over TBB kernels —
// block or point multicolour smoothing, row-parallel residuals and transfers on row-major blocks, the
// Galerkin product gathered in parallel, CHOLMOD on the coarsest level.
#include <Eigen/CholmodSupport>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <vector>

#include "fairshape/solver/block_ordering.h"
#include "fairshape/solver/multigrid.h"
#include "fairshape/solver/parallel_kernels.h"
#include "fairshape/solver/row_kernels.h"
#include "fairshape/solver/symmetric_rows.h"

namespace fairshape {
namespace {

// PatchSmoother::apply_patch on row-major blocks of C columns: x_p += A_pp⁻¹ (b − A x)_p with
// the residual by the row kernels and the product as a sum of the inverse's columns, each
// column of e contiguous so that the innermost loop vectorizes.
template <int C>
void apply_patch(const PatchSmoother& p, std::size_t k, const CsrView& A, double* x, const double* b,
                 double* __restrict r, double* __restrict e) {
  const std::vector<int>& patch = p.patch(k);
  const auto m = static_cast<std::ptrdiff_t>(patch.size());
  for (std::ptrdiff_t a = 0; a < m; ++a) {
    double s[C];
    row_sum<C>(A, patch[static_cast<std::size_t>(a)], x, s);
    for (int c = 0; c < C; ++c) r[c * m + a] = b[patch[static_cast<std::size_t>(a)] * C + c] - s[c];
  }
  const double* __restrict inverse = p.inverse(k);
  std::fill(e, e + C * m, 0.0);
  for (std::ptrdiff_t q = 0; q < m; ++q)
    for (int c = 0; c < C; ++c) {
      const double rq = r[c * m + q];
      for (std::ptrdiff_t a = 0; a < m; ++a) e[c * m + a] += inverse[q * m + a] * rq;
    }
  for (std::ptrdiff_t a = 0; a < m; ++a)
    for (int c = 0; c < C; ++c) x[patch[static_cast<std::size_t>(a)] * C + c] += e[c * m + a];
}

class ParallelKernels {
 public:
  using Block = RowBlock;

  // Each level's operator is read as rows (symmetric: no transposed copy), renumbered into
  // the one copy the kernels keep, and its column-major original released at once; the
  // finest one is the caller's A (at 4.5M unknowns every copy of it is 0.9 GB).
  void setup(const SparseMatrix& fine, MultigridLevels levels, const MultigridOptions& options) {
    omega_ = options.omega;
    block_ = options.smoother == MultigridOptions::Smoother::Block;
    const std::size_t n = levels.size();
    A_.resize(n);
    P_.assign(n, {});
    PT_.assign(n, {});
    orderings_.assign(n, {});
    smoothers_.assign(n, {});
    block_smoothers_.assign(n, {});
    patches_.assign(n, {});
    for (std::size_t l = 1; l < n; ++l) {  // the coarsest level is solved directly, in its own numbering
      const SparseMatrix& op = l + 1 == n ? fine : levels[l].A;
      if (block_) {
        orderings_[l] = BlockOrdering::build(rows_of_symmetric(op), BlockOrdering::block_size_for(op.rows(), options.block_size));
        A_[l] = orderings_[l].permute(rows_of_symmetric(op));
        block_smoothers_[l].analyze(A_[l], orderings_[l].color_blocks);
      } else {
        A_[l] = rows_of_symmetric(op);
        smoothers_[l].analyze(A_[l]);
      }
      levels[l].A = SparseMatrix();
      P_[l] = block_ ? permute_prolongation(levels[l].P, orderings_[l], orderings_[l - 1]) : levels[l].P;
      levels[l].P = SparseMatrix();
      PT_[l] = RowSparseMatrix(SparseMatrix(P_[l]).transpose());
      std::vector<std::vector<int>> patches = std::move(levels[l].patches);
      if (block_)
        for (auto& patch : patches)
          for (int& i : patch) i = orderings_[l].new_of_old[static_cast<std::size_t>(i)];
      patches_[l].setup(A_[l], patches);
    }
    A_[0] = levels[0].A;
    coarse_.compute(levels[0].A, options.coarse_space == MultigridOptions::CoarseSpace::Truncated);
  }

  int levels() const { return static_cast<int>(A_.size()); }
  Block zeros(int l, Eigen::Index cols) const { return Block::Zero(A_[l].rows(), cols); }
  void smooth(int l, Block& x, const Block& b, int sweeps, bool forward) const {
    if (!forward) patch_pass(l, x, b, false);
    for (int s = 0; s < sweeps; ++s)
      if (block_) block_smoothers_[l].sweep(A_[l], x, b, omega_, forward);
      else smoothers_[l].sweep(A_[l], x, b, omega_, forward);
    if (forward) patch_pass(l, x, b, true);
  }
  // The patch smoother's colours in turn, each colour's patches in parallel.
  void patch_pass(int l, Block& x, const Block& b, bool forward) const {
    const PatchSmoother& p = patches_[l];
    if (p.empty()) return;
    const CsrView A(A_[l]);
    const auto& colors = p.colors();
    with_columns(x.cols(), [&](auto C) {
      for (std::size_t q = 0; q < colors.size(); ++q) {
        const auto& patches = colors[forward ? q : colors.size() - 1 - q];
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, patches.size(), 16), [&](const tbb::blocked_range<std::size_t>& r) {
          std::vector<double> scratch(static_cast<std::size_t>(2 * C * p.max_size()));
          for (std::size_t i = r.begin(); i != r.end(); ++i)
            apply_patch<C>(p, patches[i], A, x.data(), b.data(), scratch.data(), scratch.data() + C * p.max_size());
        });
      }
    });
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
  bool coarse_solve(const Block& b, Block& x) { return coarse_.solve(b, x); }
  Eigen::VectorXd column_dots(const Block& a, const Block& c) const { return parallel_column_dots(a, c); }
  // The caller's vectors are in the system's numbering; the finest level may be renumbered.
  Block to_block(const Eigen::MatrixXd& m) const {
    const BlockOrdering& o = orderings_.back();
    if (o.empty()) return m;
    Block out(m.rows(), m.cols());
    for (Eigen::Index i = 0; i < m.rows(); ++i) out.row(o.new_of_old[static_cast<std::size_t>(i)]) = m.row(i);
    return out;
  }
  Eigen::MatrixXd from_block(const Block& m) const {
    const BlockOrdering& o = orderings_.back();
    if (o.empty()) return m;
    Eigen::MatrixXd out(m.rows(), m.cols());
    for (Eigen::Index i = 0; i < m.rows(); ++i) out.row(i) = m.row(o.new_of_old[static_cast<std::size_t>(i)]);
    return out;
  }

 private:
  std::vector<RowSparseMatrix> A_, P_, PT_;
  std::vector<BlockOrdering> orderings_;  // empty: the level keeps its numbering
  std::vector<MulticolorSmoother> smoothers_;
  std::vector<BlockSmoother> block_smoothers_;
  std::vector<PatchSmoother> patches_;
  CoarsestSolve<Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>> coarse_;
  double omega_ = 1.0;
  bool block_ = true;
};

}  // namespace

std::unique_ptr<Solver> make_parallel_multigrid(Config& cfg) {
  return make_multigrid_solver<ParallelKernels>(cfg, false, parallel_galerkin_product);
}

std::unique_ptr<Solver> make_parallel_multigrid_cg(Config& cfg) {
  return make_multigrid_solver<ParallelKernels>(cfg, true, parallel_galerkin_product);
}

}  // namespace fairshape
