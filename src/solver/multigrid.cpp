#include "fairshape/solver/multigrid.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "fairshape/core/error.h"
#include "fairshape/problem/constrained_system.h"
#include "fairshape/solver/symmetric_rows.h"

namespace fairshape {

namespace {

using Cycle = MultigridOptions::Cycle;
using CoarseOperator = MultigridOptions::CoarseOperator;
using CoarseSpace = MultigridOptions::CoarseSpace;
using Smoother = MultigridOptions::Smoother;

const NameTable<Cycle>& cycle_names() {
  static const NameTable<Cycle> t{{Cycle::V, "v"}, {Cycle::W, "w"}, {Cycle::Fmg, "fmg"}};
  return t;
}
const NameTable<CoarseOperator>& coarse_operator_names() {
  static const NameTable<CoarseOperator> t{{CoarseOperator::Galerkin, "galerkin"},
                                           {CoarseOperator::Reassembly, "reassembly"}};
  return t;
}
const NameTable<CoarseSpace>& coarse_space_names() {
  static const NameTable<CoarseSpace> t{{CoarseSpace::Nested, "nested"},
                                        {CoarseSpace::Truncated, "truncated"},
                                        {CoarseSpace::Conforming, "conforming"}};
  return t;
}
const NameTable<Smoother>& smoother_names() {
  static const NameTable<Smoother> t{{Smoother::Block, "block"}, {Smoother::Multicolor, "multicolor"}};
  return t;
}

}  // namespace

MultigridOptions MultigridOptions::from_config(Config& cfg) {
  MultigridOptions o;
  Config sub = cfg.child("multigrid", "options of the multigrid solvers");
  o.cycle = sub.get_enum("cycle", o.cycle, cycle_names(),
                         "v / w cycles, or full multigrid (fmg: coarse-to-fine start, then v-cycles)");
  o.coarse_operator = sub.get_enum("coarse_operator", o.coarse_operator, coarse_operator_names(),
                                   "coarse operators: Galerkin product PᵀAP, or the energy re-assembled on "
                                   "each coarser mesh");
  o.coarse_space = sub.get_enum(
      "coarse_space", o.coarse_space, coarse_space_names(),
      "coarse unknowns: nested (coarse vertices whose own fine vertex is free), truncated (every coarse vertex "
      "whose subdivided basis function reaches a free fine vertex, cut to the free ones; with coarse_operator "
      "reassembly it is nested) or conforming (only those whose basis function vanishes on every constrained "
      "fine vertex)");
  o.pre_smooth = sub.get_int("pre_smooth", o.pre_smooth, 0, 1000, "forward smoothing sweeps before the coarse correction");
  o.post_smooth = sub.get_int("post_smooth", o.post_smooth, 0, 1000, "backward smoothing sweeps after it");
  o.omega = sub.get<double>("omega", o.omega, "smoother relaxation in (0, 2): 1 = Gauss-Seidel, else SOR");
  if (!(o.omega > 0.0 && o.omega < 2.0))
    throw InvalidConfig(sub.key_path("omega") + ": " + std::to_string(o.omega) + " is outside (0, 2), where SOR diverges");
  o.patch_smoothing = sub.get<bool>("patch_smoothing", o.patch_smoothing,
                                    "exact solves on patches around extraordinary vertices after each sweep set");
  o.stiff_stars = sub.get_number("stiff_stars", o.stiff_stars, 0.0, 1e12,
                                  "star patches (a vertex and its faces' vertices) where the diagonal of A times the "
                                  "local mesh size h⁴ exceeds this multiple of its median: the energy's stiff spots "
                                  "(0: none; needs patch_smoothing)");
  if (!o.patch_smoothing && o.stiff_stars > 0 && sub.has("stiff_stars") && !sub.documenting())
    throw InvalidConfig(sub.key_path("stiff_stars") + ": star patches run in the patch smoother, which patch_smoothing: "
                        "false turns off (set stiff_stars: 0, or patch_smoothing: true)");
  o.smoother = sub.get_enum(
      "smoother", o.smoother, smoother_names(),
      "optimized back end: block multicolour Gauss-Seidel on a renumbered system (contiguous blocks) or point "
      "multicolour on the subdivision numbering; the reference is lexicographic either way");
  o.block_size = sub.get_int("block_size", o.block_size, 16, 1 << 16, "largest rows per block of the block smoother (a level uses smaller blocks when it has fewer than 64 of them)");
  o.max_levels = sub.get_int("max_levels", o.max_levels, 0, 64, "coarse levels to use (0: all the hierarchy has)");
  if (o.pre_smooth + o.post_smooth == 0 && !sub.documenting())
    throw InvalidConfig(sub.path() + ": pre_smooth and post_smooth are both 0: the cycle would not smooth");
  sub.check_no_unknown_keys();
  return o;
}

void PatchSmoother::setup(const RowSparseMatrix& A, const std::vector<std::vector<int>>& patches) {
  patches_ = patches;
  inverses_.clear();
  offsets_.clear();
  max_size_ = 0;
  for (const auto& patch : patches_) {
    const auto m = static_cast<Eigen::Index>(patch.size());
    Eigen::MatrixXd Apq(m, m);
    for (Eigen::Index a = 0; a < m; ++a)
      for (Eigen::Index c = 0; c < m; ++c) Apq(a, c) = A.coeff(patch[a], patch[c]);
    // A principal block of a positive definite matrix: LDLᵀ gives its inverse stably.
    const Eigen::MatrixXd solved = Eigen::LDLT<Eigen::MatrixXd>(Apq).solve(Eigen::MatrixXd::Identity(m, m));
    const Eigen::MatrixXd inverse = 0.5 * (solved + solved.transpose());  // exactly symmetric (apply_patch)
    offsets_.push_back(inverses_.size());
    inverses_.insert(inverses_.end(), inverse.data(), inverse.data() + inverse.size());
    max_size_ = std::max(max_size_, m);
  }
  // Colours: patch q conflicts with p when one of q's rows is coupled (through A) to p's rows.
  std::vector<std::vector<std::size_t>> owners(static_cast<std::size_t>(A.rows()));
  for (std::size_t k = 0; k < patches_.size(); ++k)
    for (int i : patches_[k]) owners[static_cast<std::size_t>(i)].push_back(k);
  std::vector<int> color(patches_.size(), -1), taken_by;  // taken_by[c] == p: a conflict of p has c
  colors_.clear();
  for (std::size_t k = 0; k < patches_.size(); ++k) {
    for (int i : patches_[k])
      for (RowSparseMatrix::InnerIterator it(A, i); it; ++it)
        for (std::size_t q : owners[static_cast<std::size_t>(it.col())])
          if (q != k && color[q] >= 0) taken_by[static_cast<std::size_t>(color[q])] = static_cast<int>(k);
    int c = 0;
    while (c < static_cast<int>(taken_by.size()) && taken_by[static_cast<std::size_t>(c)] == static_cast<int>(k)) ++c;
    if (c == static_cast<int>(taken_by.size())) {
      taken_by.push_back(-1);
      colors_.emplace_back();
    }
    color[k] = c;
    colors_[static_cast<std::size_t>(c)].push_back(k);
  }
}

bool coarse_solve_accurate(const SparseMatrix& A, const Eigen::MatrixXd& b, const Eigen::MatrixXd& x) {
  const double scale = b.norm() > 0 ? b.norm() : 1.0;
  return (b - A * x).norm() <= 1e-8 * scale;
}

SparseMatrix regularized_for_factorization(const SparseMatrix& A) {
  SparseMatrix out = A;
  for (Eigen::Index i = 0; i < out.rows(); ++i) out.coeffRef(i, i) *= 1.0 + 1e-10;
  return out;
}

SparseMatrix serial_galerkin_product(const SparseMatrix& A, const SparseMatrix& P) {
  return SparseMatrix(SparseMatrix(P.transpose()) * (A * P));
}

namespace {

// M[rows, cols] with the kept ids renumbered 0..; `col_of` maps an old column to its new id or −1.
SparseMatrix select(const SparseMatrix& M, const std::vector<int>& rows, const std::vector<int>& col_of, int n_cols) {
  const RowSparseMatrix R(M);
  Triplets t;
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (RowSparseMatrix::InnerIterator it(R, rows[i]); it; ++it)
      if (col_of[it.col()] >= 0) t.emplace_back(static_cast<int>(i), col_of[it.col()], it.value());
  SparseMatrix out(static_cast<Eigen::Index>(rows.size()), n_cols);
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

// A reproducible vector with entries in [−1, 1] (a plain LCG: no dependence on the library's RNG).
Eigen::VectorXd probe(Eigen::Index n) {
  Eigen::VectorXd v(n);
  std::uint64_t s = 0x9e3779b97f4a7c15ull;
  for (Eigen::Index i = 0; i < n; ++i) {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    v[i] = static_cast<double>(s >> 11) / static_cast<double>(1ull << 53) * 2.0 - 1.0;
  }
  return v;
}

// One patch per singular vertex of hierarchy level `level` that the system keeps: the
// unknown and its neighbours in A (per coordinate block).
std::vector<std::vector<int>> singular_patches(const SparseMatrix& A, const std::vector<int>& kept, int level,
                                               const LevelOperators& ops, int blocks) {
  if (level >= static_cast<int>(ops.singular.size()) || ops.singular[level].empty()) return {};
  const Eigen::Index n_vertices = level == 0 ? ops.prolongation[0].cols() : ops.prolongation[level - 1].rows();
  std::vector<int> local(static_cast<std::size_t>(blocks * n_vertices), -1);
  for (std::size_t i = 0; i < kept.size(); ++i) local[kept[i]] = static_cast<int>(i);
  const auto R = rows_of_symmetric(A);
  std::vector<std::vector<int>> patches;
  for (int b = 0; b < blocks; ++b)
    for (int v : ops.singular[level]) {
      const int row = local[b * n_vertices + v];
      if (row < 0) continue;
      std::vector<int> patch;
      for (SymmetricRows::InnerIterator it(R, row); it; ++it) patch.push_back(static_cast<int>(it.col()));
      patches.push_back(std::move(patch));
    }
  return patches;
}

// Stiff stars (papers/boier-martin/README.md). The divided differences of a local quadratic fit on a
// near-degenerate ring are large, so the energy there is far stiffer than a fourth-order
// operator on that mesh size (diag ∝ h⁻⁴) would be: on the hand model diag(A)·h⁴ spans four
// orders of magnitude. Gauss-Seidel and the subdivision coarse space then both leave a band
// of smooth-looking modes (two-grid contraction 0.991 on the hand, the same at levels 3 and 4);
// an exact solve on each stiff vertex's star after the sweeps brings it to 0.88 (ratio 5, 11 % of
// the vertices; the default 20 keeps most of the gain at a fraction of the cost: measured in
// papers/boier-martin/README.md, "Stiff stars"). One patch per such vertex and coordinate block,
// at most a quarter of the level's vertices (the stiffest).
std::vector<std::vector<int>> stiff_star_patches(const SparseMatrix& A, const std::vector<int>& kept,
                                                 const VertexStars& stars, int blocks, double ratio) {
  const auto n_vertices = static_cast<Eigen::Index>(stars.size2.size());
  if (ratio <= 0 || n_vertices == 0 || static_cast<Eigen::Index>(stars.offsets.size()) != n_vertices + 1) return {};
  std::vector<int> local(static_cast<std::size_t>(blocks * n_vertices), -1);
  for (std::size_t i = 0; i < kept.size(); ++i) local[static_cast<std::size_t>(kept[i])] = static_cast<int>(i);
  std::vector<std::pair<double, int>> stiffness;  // (diag · h⁴, vertex), vertices of the first block kept
  for (Eigen::Index v = 0; v < n_vertices; ++v)
    if (const int row = local[static_cast<std::size_t>(v)]; row >= 0)
      stiffness.emplace_back(A.coeff(row, row) * stars.size2[v] * stars.size2[v], static_cast<int>(v));
  if (stiffness.empty()) return {};
  std::vector<std::pair<double, int>> sorted = stiffness;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const double threshold = ratio * sorted[sorted.size() / 2].first;
  std::vector<std::pair<double, int>> stiff;
  for (const auto& s : stiffness)
    if (s.first > threshold) stiff.push_back(s);
  const std::size_t cap = stiffness.size() / 4;
  if (stiff.size() > cap) {
    std::nth_element(stiff.begin(), stiff.begin() + static_cast<std::ptrdiff_t>(cap), stiff.end(), std::greater<>());
    stiff.resize(cap);
    std::sort(stiff.begin(), stiff.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  }
  std::vector<std::vector<int>> patches;
  for (int b = 0; b < blocks; ++b)
    for (const auto& s : stiff) {
      std::vector<int> patch;
      for (int k = stars.offsets[static_cast<std::size_t>(s.second)]; k < stars.offsets[static_cast<std::size_t>(s.second) + 1]; ++k)
        if (const int row = local[static_cast<std::size_t>(b * n_vertices + stars.ids[static_cast<std::size_t>(k)])]; row >= 0)
          patch.push_back(row);
      std::sort(patch.begin(), patch.end());
      if (patch.size() > 1) patches.push_back(std::move(patch));
    }
  return patches;
}

// Rows next to the constrained unknowns lose the interpolation weight of the coarse unknowns
// the system dropped: there the coarse space misses the local behaviour of a fourth-order
// solution at its pinned boundary, as it does at extraordinary vertices. One patch per
// such row (its neighbours in A).
std::vector<std::vector<int>> truncated_patches(const SparseMatrix& A, const SparseMatrix& P_full,
                                                const std::vector<int>& kept, const SparseMatrix& P) {
  const Eigen::VectorXd full_sums = P_full * Eigen::VectorXd::Ones(P_full.cols());
  const Eigen::VectorXd kept_sums = P * Eigen::VectorXd::Ones(P.cols());
  const auto R = rows_of_symmetric(A);
  std::vector<std::vector<int>> patches;
  for (std::size_t i = 0; i < kept.size(); ++i) {
    if (std::abs(full_sums[kept[i]] - kept_sums[static_cast<Eigen::Index>(i)]) <= 1e-12) continue;
    std::vector<int> patch;
    for (SymmetricRows::InnerIterator it(R, static_cast<Eigen::Index>(i)); it; ++it) patch.push_back(static_cast<int>(it.col()));
    patches.push_back(std::move(patch));
  }
  return patches;
}

// Which coarse unknowns the level keeps, ascending (see MultigridOptions::CoarseSpace).
// `nf`, `ncv`: fine and coarse vertices per coordinate block (vertex ids nest across levels).
std::vector<int> coarse_unknowns(const SparseMatrix& P_full, const std::vector<int>& kept, Eigen::Index nf,
                                 Eigen::Index ncv, MultigridOptions::CoarseSpace space) {
  std::vector<char> fine_kept(static_cast<std::size_t>(P_full.rows()), 0);
  for (int i : kept) fine_kept[static_cast<std::size_t>(i)] = 1;
  std::vector<int> out;
  if (space == MultigridOptions::CoarseSpace::Truncated) {
    for (Eigen::Index column = 0; column < P_full.cols(); ++column)
      for (SparseMatrix::InnerIterator it(P_full, column); it; ++it)
        if (it.value() != 0.0 && fine_kept[static_cast<std::size_t>(it.row())]) {
          out.push_back(static_cast<int>(column));
          break;
        }
    return out;
  }
  const auto conforms = [&](Eigen::Index column) {
    for (SparseMatrix::InnerIterator it(P_full, column); it; ++it)
      if (it.value() != 0.0 && !fine_kept[static_cast<std::size_t>(it.row())]) return false;
    return true;
  };
  for (int i : kept) {
    const Eigen::Index block = i / nf, vertex = i % nf;
    if (vertex >= ncv) continue;
    const Eigen::Index column = block * ncv + vertex;
    if (space == MultigridOptions::CoarseSpace::Conforming && !conforms(column)) continue;
    out.push_back(static_cast<int>(column));
  }
  return out;
}

}  // namespace

MultigridLevels build_multigrid_levels(const SparseMatrix& A, const LevelOperators& ops, const LevelSelection& selection,
                                       const MultigridOptions& opt, const GalerkinProduct& galerkin) {
  const int available = ops.coarse_levels();
  if (available == 0)
    throw InvalidInput("multigrid: the hierarchy has no coarser level (set input.levels >= 1 and edit a finer level)");
  const int used = opt.max_levels > 0 ? std::min(opt.max_levels, available) : available;
  if (opt.coarse_operator == MultigridOptions::CoarseOperator::Reassembly && !ops.reassemble)
    throw InvalidInput("multigrid: coarse_operator reassembly needs the energy on every level, which this problem does not provide");
  const Eigen::Index n_full = selection.blocks * ops.prolongation.back().rows();
  std::vector<int> kept = selection.kept;
  if (kept.empty())
    for (int i = 0; i < n_full; ++i) kept.push_back(i);
  if (static_cast<Eigen::Index>(kept.size()) != A.rows())
    throw InvalidInput("multigrid: the system has " + std::to_string(A.rows()) + " unknowns, the hierarchy's kept set " +
                       std::to_string(kept.size()));
  // A re-assembled operator knows nothing of cut functions: it pins the coarse vertices itself.
  const auto space = opt.coarse_operator == MultigridOptions::CoarseOperator::Reassembly &&
                             opt.coarse_space == MultigridOptions::CoarseSpace::Truncated
                         ? MultigridOptions::CoarseSpace::Nested
                         : opt.coarse_space;
  MultigridLevels levels(used + 1);
  // The finest level's operator is the caller's A, not copied (see MultigridLevel::A).
  const auto op = [&](int k) -> const SparseMatrix& { return k == used ? A : levels[k].A; };
  for (int k = used; k > 0; --k) {
    const int level = available - (used - k) - 1;  // the hierarchy's level below level k's
    const SparseMatrix P_full = block_diagonal(ops.prolongation[level], selection.blocks);
    const std::vector<int> coarse_kept = coarse_unknowns(P_full, kept, ops.prolongation[level].rows(),
                                                         ops.prolongation[level].cols(), space);
    std::vector<int> col_of(P_full.cols(), -1);
    for (std::size_t c = 0; c < coarse_kept.size(); ++c) col_of[static_cast<std::size_t>(coarse_kept[c])] = static_cast<int>(c);
    if (coarse_kept.empty())
      throw InvalidInput("multigrid: no coarse unknown on hierarchy level " + std::to_string(level) +
                         " stays clear of the constrained vertices; lower multigrid.max_levels");
    const int nc = static_cast<int>(coarse_kept.size());
    levels[k].P = select(P_full, kept, col_of, nc);
    if (opt.coarse_operator == MultigridOptions::CoarseOperator::Galerkin) {
      levels[k - 1].A = galerkin(op(k), levels[k].P);
    } else {
      const SparseMatrix H = select(block_diagonal(ops.reassemble(level), selection.blocks), coarse_kept, col_of, nc);
      // The re-assembled energy differs from the Galerkin operator by a level-dependent factor
      // (it counts each level's vertices once): match their Rayleigh quotients on a smooth-ish
      // vector (a random one after damped Jacobi steps with H; on a rough one the ratio is that
      // of the high frequencies).
      Eigen::VectorXd v = probe(nc);
      const Eigen::VectorXd inv_diag = H.diagonal().cwiseInverse();
      for (int step = 0; step < 30; ++step) v -= 0.5 * inv_diag.cwiseProduct(H * v);
      const Eigen::VectorXd Pv = levels[k].P * v;
      const double scale = Pv.dot(op(k) * Pv) / v.dot(H * v);
      if (!(scale > 0 && std::isfinite(scale)))
        throw InvalidInput("multigrid: the re-assembled operator of level " + std::to_string(level) +
                           " is not positive on the coarse space");
      levels[k - 1].A = scale * H;
    }
    if (opt.patch_smoothing) {
      levels[k].patches = singular_patches(op(k), kept, level + 1, ops, selection.blocks);
      for (auto& patch : truncated_patches(op(k), P_full, kept, levels[k].P)) levels[k].patches.push_back(std::move(patch));
      // Where singular vertices are dense (the first levels above a triangle mesh) the patches
      // would cost many sweeps and overlap everywhere: those levels rely on the sweeps alone.
      if (levels[k].patches.size() * 8 > kept.size()) levels[k].patches.clear();
      if (ops.stars)
        for (auto& patch : stiff_star_patches(op(k), kept, ops.stars(level + 1), selection.blocks, opt.stiff_stars))
          levels[k].patches.push_back(std::move(patch));
    }
    kept = coarse_kept;
  }
  return levels;
}

}  // namespace fairshape
