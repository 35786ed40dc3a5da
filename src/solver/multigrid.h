// Multigrid for the symmetric positive definite systems of the design problems, on the levels
// of a multiresolution representation (LevelOperators). Boier-Martin et al. §5 run a
// coarse-to-fine cascade without restriction and name "a full-fledged multigrid
// implementation including restriction" as future work; this is that solver:
//   - transfers: prolongation P_l (the subdivision operator, restricted to the unknowns the
//     system keeps) and restriction by its transpose, so every coarse correction minimizes
//     the fine energy over the coarse space (the variational setting of Hackbusch's book);
//   - coarse operators: the Galerkin product Pᵀ A P, or the energy re-assembled on the coarse
//     mesh (cheaper, approximate) and scaled to match the Galerkin operator's Rayleigh quotient;
//   - V-, W-cycles and full multigrid (FMG), forward Gauss-Seidel/SOR before the coarse
//     correction and backward after it (a symmetric cycle, so it also preconditions CG),
//     a direct factorization on the coarsest level.
// The cycle is written once, over a Kernels type that supplies the level operations; the
// reference and optimized back ends differ only in their kernels.
#pragma once

#include <Eigen/Dense>

#include <memory>
#include <string>
#include <vector>

#include "fairshape/core/config.h"
#include "fairshape/core/error.h"
#include "fairshape/solver/iterative.h"
#include "fairshape/solver/level_operators.h"
#include "fairshape/solver/matrix_fingerprint.h"

namespace fairshape {

// Why patches: subdivision prolongation reproduces cubics in regular regions but only linear
// functions at extraordinary vertices, which is not enough for fourth-order energies (the
// order rule m_P + m_R > 2m of Hackbusch's book fails there). Error modes near each such
// vertex are then neither smoothed nor corrected, and a cycle stalls near 0.95 on a mesh that
// came from triangles (thousands of them). Solving exactly on a small patch around each
// singular vertex after the sweeps (a multiplicative Schwarz step) removes those modes.
struct MultigridOptions {
  enum class Cycle { V, W, Fmg };
  enum class CoarseOperator { Galerkin, Reassembly };
  //! Which coarse vertices stay unknowns next to the constrained (dropped) fine vertices:
  //! Nested: the coarse vertices whose own fine vertex is free.
  //! Truncated: every coarse basis function that reaches a free fine vertex, cut to the free
  //!   ones (as truncated B-splines at a cut boundary). The largest space, so the coarse
  //!   correction reaches the band next to the pinned region; some cut functions coincide
  //!   there, so the coarse operators may be singular (consistent: the coarsest solve is
  //!   regularized and refined, see solve_coarsest).
  //! Conforming: only the functions that vanish on every constrained fine vertex.
  //! Measured in papers/boier-martin (README, "coarse spaces").
  enum class CoarseSpace { Nested, Truncated, Conforming };
  Cycle cycle = Cycle::V;
  CoarseOperator coarse_operator = CoarseOperator::Galerkin;
  CoarseSpace coarse_space = CoarseSpace::Nested;
  int pre_smooth = 2, post_smooth = 2;
  double omega = 1.0;  // smoother relaxation: 1 = Gauss-Seidel
  int max_levels = 0;  // coarse levels to use (0: every level the hierarchy offers)
  bool patch_smoothing = true;  // exact solves on patches around singular vertices
  //! Star patches where diag(A)·h⁴ exceeds this multiple of its median (0: none; see
  //! stiff_star_patches in multigrid.cpp). Only with patch_smoothing and stars from the hierarchy.
  double stiff_stars = 20.0;
  //! Optimized back end's smoother: point multicolour over the subdivision numbering, or block
  //! multicolour over a renumbering that keeps blocks contiguous (block_ordering.h).
  enum class Smoother { Multicolor, Block };
  Smoother smoother = Smoother::Block;
  int block_size = 4096;  // the largest; small levels use smaller blocks (BlockOrdering::block_size_for)
  //! Reads the `multigrid` block of a solver's options.
  static MultigridOptions from_config(Config& cfg);
};

struct MultigridLevel {
  //! The operator on this level's unknowns; empty on the finest level, whose operator is the
  //! system's own matrix (kernels get it beside the levels: a copy is 0.9 GB at 4.5M unknowns).
  SparseMatrix A;
  SparseMatrix P;  // from the next coarser level (empty on the coarsest)
  std::vector<std::vector<int>> patches;  // unknowns around each singular vertex
};

//! Multiplicative Schwarz on small overlapping patches: x_p += A_pp⁻¹ (b − A x)_p. The patches
//! are coloured so that two of one colour never touch each other's rows through A: a colour's
//! patches may run in any order, or in parallel, with bit-identical results. A pass runs the
//! colours in order (in reverse for the adjoint pass). The inverses are formed once (patches are
//! a few dozen unknowns), so a pass allocates nothing but two small buffers.
class PatchSmoother {
 public:
  void setup(const RowSparseMatrix& A, const std::vector<std::vector<int>>& patches);
  bool empty() const { return patches_.empty(); }
  const std::vector<std::vector<std::size_t>>& colors() const { return colors_; }
  Eigen::Index max_size() const { return max_size_; }
  const std::vector<int>& patch(std::size_t k) const { return patches_[k]; }
  //! A_pp⁻¹ of patch k: m × m, exactly symmetric (so column q is also row q).
  const double* inverse(std::size_t k) const { return inverses_.data() + offsets_[k]; }

  //! The serial pass (the reference back end; the optimized one runs each colour in parallel).
  template <class Block>
  void apply(const RowSparseMatrix& A, Block& x, const Block& b, bool forward) const {
    if (patches_.empty()) return;
    Eigen::MatrixXd r(max_size_, x.cols()), e(max_size_, x.cols());
    const std::size_t n = colors_.size();
    for (std::size_t q = 0; q < n; ++q)
      for (std::size_t k : colors_[forward ? q : n - 1 - q]) apply_patch(k, A, x, b, r, e);
  }
  //! One patch; r and e are scratch of max_size() rows.
  template <class Block>
  void apply_patch(std::size_t k, const RowSparseMatrix& A, Block& x, const Block& b, Eigen::MatrixXd& r,
                   Eigen::MatrixXd& e) const {
    const std::vector<int>& patch = patches_[k];
    const auto m = static_cast<Eigen::Index>(patch.size());
    for (Eigen::Index a = 0; a < m; ++a) {
      for (Eigen::Index c = 0; c < x.cols(); ++c) r(a, c) = b(patch[a], c);
      for (RowSparseMatrix::InnerIterator it(A, patch[a]); it; ++it)
        for (Eigen::Index c = 0; c < x.cols(); ++c) r(a, c) -= it.value() * x(it.col(), c);
    }
    // e = A_pp⁻¹ r by hand, as a sum of the inverse's columns: at a few dozen rows a general
    // matrix product spends more time packing its operands than multiplying, and a dot
    // product per entry waits on one chain of additions.
    const double* inverse = this->inverse(k);
    e.topRows(m).setZero();
    for (Eigen::Index q = 0; q < m; ++q)
      for (Eigen::Index c = 0; c < x.cols(); ++c)
        for (Eigen::Index a = 0; a < m; ++a) e(a, c) += inverse[q * m + a] * r(q, c);
    for (Eigen::Index a = 0; a < m; ++a)
      for (Eigen::Index c = 0; c < x.cols(); ++c) x(patch[a], c) += e(a, c);
  }

 private:
  std::vector<std::vector<int>> patches_;
  std::vector<std::vector<std::size_t>> colors_;  // patch indices per colour, ascending
  std::vector<double> inverses_;  // A_pp⁻¹ of every patch, column-major, back to back
  std::vector<std::size_t> offsets_;
  Eigen::Index max_size_ = 0;
};

//! A direct solve is trusted when its relative residual is small: a semidefinite coarsest
//! operator (nothing pinned) can factor "successfully" and return garbage.
bool coarse_solve_accurate(const SparseMatrix& A, const Eigen::MatrixXd& b, const Eigen::MatrixXd& x);

//! What the coarsest level factors: A with its diagonal raised by a relative 1e-10. The
//! truncated coarse space can make A singular (two cut functions equal on the free vertices);
//! the systems the cycle hands down stay consistent, and any solution gives the same
//! prolongated correction. Refinement against A itself (solve_coarsest) removes the shift.
SparseMatrix regularized_for_factorization(const SparseMatrix& A);

//! x = A⁻¹ b through `factor` (of regularized_for_factorization(A)) with iterative refinement
//! until coarse_solve_accurate; false when it does not get there (an inconsistent, i.e.
//! truly singular, system: nothing pinned) or produces non-finite values.
template <class Factor, class Block>
bool solve_coarsest(const Factor& factor, const SparseMatrix& A, const Block& b_in, Block& x_out) {
  constexpr int kMaxRefinements = 8;
  const Eigen::MatrixXd b = b_in;
  Eigen::MatrixXd x = factor.solve(b);
  for (int k = 0; k < kMaxRefinements && x.allFinite() && !coarse_solve_accurate(A, b, x); ++k)
    x += factor.solve(Eigen::MatrixXd(b - A * x));
  x_out = x;
  return x.allFinite() && coarse_solve_accurate(A, b, x);
}

//! The coarsest level's direct solve. A nested or conforming coarse space gives a positive
//! definite operator: it is factored as is, and once one solve has passed
//! coarse_solve_accurate (which catches a semidefinite operator — nothing pinned — that
//! factored "successfully") every later solve is the factorization alone: the check and
//! refinement cost more than the solve (level 2 of the cow as coarsest level: ~2× the solve).
//! A truncated space, or an operator the factorization refuses, gets the regularized factor
//! and refinement on every solve (solve_coarsest).
template <class Factor>
class CoarsestSolve {
 public:
  void compute(const SparseMatrix& A, bool may_be_singular) {
    A_ = A;
    refine_always_ = may_be_singular;
    verified_ = false;
    if (!refine_always_) {
      factor_.compute(A_);
      if (factor_.info() == Eigen::Success) return;
      refine_always_ = true;
    }
    factor_.compute(regularized_for_factorization(A_));
  }
  template <class Block>
  bool solve(const Block& b, Block& x) {
    if (factor_.info() != Eigen::Success) return false;
    if (verified_ && !refine_always_) {
      x = Eigen::MatrixXd(factor_.solve(Eigen::MatrixXd(b)));
      return x.allFinite();
    }
    verified_ = solve_coarsest(factor_, A_, b, x);
    return verified_;
  }

 private:
  SparseMatrix A_;
  Factor factor_;
  bool refine_always_ = false, verified_ = false;
};

//! Level 0 = coarsest, back() = the system itself.
using MultigridLevels = std::vector<MultigridLevel>;

//! A · P and Pᵀ · A · P; back ends supply their own product.
using GalerkinProduct = std::function<SparseMatrix(const SparseMatrix& A, const SparseMatrix& P)>;
SparseMatrix serial_galerkin_product(const SparseMatrix& A, const SparseMatrix& P);

//! The levels below A: each prolongation restricted to the kept unknowns (rows) and to the
//! coarse unknowns it reaches (columns), and the coarse operators; the finest level's A is left
//! empty (it is A). A must be compressed and symmetric.
//! \throw InvalidInput when the hierarchy is too shallow (no coarse level), sizes disagree, or
//! re-assembly is asked for without a re-assembly function.
MultigridLevels build_multigrid_levels(const SparseMatrix& A, const LevelOperators& ops, const LevelSelection& selection,
                                       const MultigridOptions& opt, const GalerkinProduct& galerkin);

// ---- the cycle, shared by both back ends --------------------------------------------------
// Kernels provide, for level l (0 = coarsest):
//   Block                                   the iterate type (n_l × columns)
//   Block zeros(int l, Index cols)
//   void smooth(int l, Block& x, const Block& b, int sweeps, bool forward)
//   Block residual(int l, const Block& x, const Block& b)        b − A_l x
//   Block restrict_down(int l, const Block& r)                    P_lᵀ r  (level l−1)
//   void prolong_add(int l, const Block& e, Block& x)             x += P_l e
//   bool coarse_solve(const Block& b, Block& x)                   A_0 x = b, false if singular
//   Block multiply(int l, const Block& x)                         A_l x
//   VectorXd column_dots(const Block& a, const Block& b)           Σ_i a_ij b_ij per column j, deterministic
//   Block to_block(const MatrixXd&), MatrixXd from_block(const Block&), int levels()
template <class Kernels>
class MultigridCycles {
 public:
  using Block = typename Kernels::Block;
  MultigridCycles(Kernels& k, const MultigridOptions& opt) : k_(k), opt_(opt) {}

  //! One V- or W-cycle on level l (FMG's cycles are V-cycles).
  void cycle(int l, Block& x, const Block& b) {
    if (l == 0) {
      ok_ = k_.coarse_solve(b, x) && ok_;
      return;
    }
    k_.smooth(l, x, b, opt_.pre_smooth, true);
    const Block coarse_b = k_.restrict_down(l, k_.residual(l, x, b));
    Block e = k_.zeros(l - 1, b.cols());
    const int visits = opt_.cycle == MultigridOptions::Cycle::W ? 2 : 1;
    for (int v = 0; v < visits; ++v) cycle(l - 1, e, coarse_b);
    k_.prolong_add(l, e, x);
    k_.smooth(l, x, b, opt_.post_smooth, false);
  }

  //! Full multigrid: b restricted to every level, solved directly on the coarsest, and each
  //! level started from the prolongated coarser solution and improved by one cycle.
  void full_multigrid(Block& x, const Block& b) {
    const int top = k_.levels() - 1;
    std::vector<Block> rhs(top + 1);
    rhs[top] = b;
    for (int l = top; l > 0; --l) rhs[l - 1] = k_.restrict_down(l, rhs[l]);
    Block coarse = k_.zeros(0, b.cols());
    ok_ = k_.coarse_solve(rhs[0], coarse) && ok_;
    for (int l = 1; l <= top; ++l) {
      Block fine = k_.zeros(l, b.cols());
      k_.prolong_add(l, coarse, fine);
      cycle(l, fine, rhs[l]);
      coarse = std::move(fine);
    }
    x = std::move(coarse);
  }

  bool ok() const { return ok_; }

 private:
  Kernels& k_;
  MultigridOptions opt_;
  bool ok_ = true;
};

//! Multigrid as a solver (`krylov` = false: cycles until the tolerance) or as the
//! preconditioner of conjugate gradients (one cycle per iteration). A warm start (x ≠ 0)
//! skips FMG's coarse-to-fine start, which would discard it.
template <class Kernels>
SolveSummary run_multigrid(Kernels& k, const MultigridOptions& mg, const IterativeOptions& opt, bool krylov,
                           const SystemEnergy& energy, const Eigen::MatrixXd& b_in, Eigen::MatrixXd& x_out,
                           const IterationCallback& cb) {
  using Block = typename Kernels::Block;
  IterationMonitor monitor(opt, cb, energy, krylov);
  MultigridCycles<Kernels> cycles(k, mg);
  const int top = k.levels() - 1;
  const Block b = k.to_block(b_in);
  Block x = k.to_block(x_out);
  const auto norm = [&](const Block& v) { return std::sqrt(k.column_dots(v, v).sum()); };
  const double b_norm = norm(b) > 0 ? norm(b) : 1.0;
  Eigen::MatrixXd seen;  // the iterate in the caller's layout, converted only when looked at
  const auto record = [&](int it, const Block& r) {
    if (monitor.wants_iterate()) monitor.observe([&] { seen = k.from_block(x); });
    return monitor.record(it, norm(r) / b_norm, seen);
  };
  const auto failed = [&] {
    if (cycles.ok()) return false;
    monitor.fail("multigrid: the coarsest-level factorization failed (singular: is anything fixed?)");
    return true;
  };
  const bool cold = x_out.isZero(0.0);
  Block r = k.residual(top, x, b);
  if (!record(0, r)) {
    x_out = k.from_block(x);
    return monitor.summary();
  }
  if (!krylov) {
    for (int it = 1;; ++it) {
      if (it == 1 && cold && mg.cycle == MultigridOptions::Cycle::Fmg) cycles.full_multigrid(x, b);
      else cycles.cycle(top, x, b);
      if (failed()) break;
      if (!monitor.should_check(it)) continue;
      r = k.residual(top, x, b);
      if (!record(it, r)) break;
    }
    x_out = k.from_block(x);
    return monitor.summary();
  }
  // Preconditioned CG, each column its own scalars (the columns are independent systems).
  const auto precondition = [&](const Block& res) {
    Block z = k.zeros(top, res.cols());
    cycles.cycle(top, z, res);
    return z;
  };
  const auto column_dots = [&](const Block& a, const Block& c) { return k.column_dots(a, c); };
  Block z = precondition(r);
  Block p = z;
  Eigen::VectorXd rz = column_dots(r, z);
  CgErrorEstimate error(opt.error_delay);
  for (int it = 1;; ++it) {
    const Block Ap = k.multiply(top, p);
    const Eigen::VectorXd pAp = column_dots(p, Ap);
    double alpha_rz = 0;
    for (Eigen::Index j = 0; j < x.cols(); ++j) {
      const double alpha = pAp[j] != 0 ? rz[j] / pAp[j] : 0.0;
      x.col(j) += alpha * p.col(j);
      r.col(j) -= alpha * Ap.col(j);
      alpha_rz += alpha * rz[j];
    }
    if (monitor.should_check(it) && !record(it, r)) {
      // The recursive residual drifts from b − Ax: the true one decides (a restart from it).
      Block true_r = k.residual(top, x, b);
      if (!monitor.confirm_residual(it, norm(true_r) / b_norm)) break;
      r = std::move(true_r);
      z = precondition(r);
      if (failed()) break;
      p = z;
      rz = column_dots(r, z);
      continue;
    }
    if (monitor.estimates_error()) {
      error.push(alpha_rz);
      if (error.ready() && !monitor.record_error(it, error.estimate((column_dots(x, b) - column_dots(x, r)).sum()))) break;
    }
    if (!monitor.should_check(it) && it >= opt.max_iterations) break;
    z = precondition(r);
    if (failed()) break;
    const Eigen::VectorXd rz_new = column_dots(r, z);
    for (Eigen::Index j = 0; j < x.cols(); ++j) p.col(j) = z.col(j) + (rz[j] != 0 ? rz_new[j] / rz[j] : 0.0) * p.col(j);
    rz = rz_new;
  }
  x_out = k.from_block(x);
  return monitor.summary();
}

//! The solver: builds the levels in analyze() (the hierarchy comes from set_levels), then
//! runs cycles or preconditioned CG. Kernels also provide setup(A, levels, options), A the
//! finest operator (levels.back().A is empty). The levels are
//! built again when a solve brings another matrix, or after set_levels (solver.h).
template <class Kernels>
class MultigridSolver : public Solver {
 public:
  MultigridSolver(IterativeOptions opt, MultigridOptions mg, bool krylov, GalerkinProduct galerkin)
      : opt_(opt), mg_(mg), krylov_(krylov), galerkin_(std::move(galerkin)) {}
  bool uses_levels() const override { return true; }
  void set_levels(std::shared_ptr<const LevelOperators> ops, const LevelSelection& selection) override {
    ops_ = std::move(ops);
    selection_ = selection;
    analyzed_.forget();  // the levels were built from the old hierarchy
  }

  void analyze(const SparseMatrix& A) override {
    analyzed_.forget();  // until the new levels stand, so that a throw below leaves none to reuse
    if (!ops_) throw InvalidInput("multigrid: no hierarchy was given (the problem has no levels below the solve level)");
    MultigridLevels levels = build_multigrid_levels(A, *ops_, selection_, mg_, galerkin_);
    // Gauss-Seidel needs a positive diagonal on every smoothed level (not the coarsest).
    diagonal_problem_.clear();
    for (std::size_t l = 1; l < levels.size() && diagonal_problem_.empty(); ++l) {
      const SparseMatrix& op = l + 1 == levels.size() ? A : levels[l].A;
      diagonal_problem_ = diagonal_problem(op.diagonal());
    }
    kernels_.setup(A, std::move(levels), mg_);  // the kernels keep what they need, in their own layout
    analyzed_.remember(A);
  }

  SolveSummary solve(const SparseMatrix& A, const Eigen::MatrixXd& b, Eigen::MatrixXd& x,
                     const IterationCallback& cb) override {
    if (!analyzed_.is(A)) analyze(A);
    if (!diagonal_problem_.empty()) {
      SolveSummary s;
      s.message = "multigrid: " + diagonal_problem_;
      return s;
    }
    return run_multigrid(kernels_, mg_, opt_, krylov_, system_energy(A, b), b, x, cb);
  }

 private:
  IterativeOptions opt_;
  MultigridOptions mg_;
  bool krylov_;
  GalerkinProduct galerkin_;
  std::shared_ptr<const LevelOperators> ops_;
  LevelSelection selection_;
  Kernels kernels_;
  std::string diagonal_problem_;
  AnalyzedMatrix analyzed_;
};

template <class Kernels>
std::unique_ptr<Solver> make_multigrid_solver(Config& cfg, bool krylov, GalerkinProduct galerkin) {
  const auto opt = IterativeOptions::from_config(cfg);
  const MultigridOptions mg = MultigridOptions::from_config(cfg);
  // CG needs a symmetric preconditioner: with unequal sweep counts it stalls instead of failing.
  if (krylov && mg.pre_smooth != mg.post_smooth && !cfg.documenting())
    throw InvalidConfig(cfg.path() + ".multigrid: multigrid_cg needs a symmetric cycle, pre_smooth (" +
                        std::to_string(mg.pre_smooth) + ") = post_smooth (" + std::to_string(mg.post_smooth) +
                        "); unequal counts are for the `multigrid` solver");
  return std::make_unique<MultigridSolver<Kernels>>(opt, mg, krylov, std::move(galerkin));
}

}  // namespace fairshape
