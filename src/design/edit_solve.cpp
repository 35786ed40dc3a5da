#include "design/edit_solve.h"

#include <Eigen/SPQRSupport>
#include <Eigen/SparseLU>
#include <Eigen/SparseQR>
#include <Eigen/UmfPackSupport>

#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <random>
#include <type_traits>

#include "core/timer.h"
#include "problem/constrained_system.h"
#include "problem/least_squares.h"
#include "qp/kkt_solver.h"
#include "qp/qp_solver.h"
#include "solver/parallel_kernels.h"

namespace fairshape {
namespace {
using ReferenceQR = Eigen::SparseQR<SparseMatrix, Eigen::COLAMDOrdering<int>>;
}  // namespace

// The Lagrange system [H s Aᵀ; s A 0] of one constraint set, factored once. Constraint rows
// are scaled by s = max diag H: on remeshed levels H's diagonal spans 1e8..1e14, and an
// unscaled K loses most digits in the LU (λ is scaled too; it is not used). Dependent rows (a
// fixed region propagated to a coarser level) make K singular: a maximal independent set is
// kept (rank-revealing sparse QR), or, when the kept rows are still nearly dependent, the
// system is regularized; the message says which. If the dropped rows disagree with the kept
// ones, constraint_residual shows it.
class KktFactorization {
 public:
  KktFactorization(const EditProblem& p, Backend backend) : H_(p.H), g_(p.g), backend_(backend) {
    const double diag_max = p.H.diagonal().cwiseAbs().maxCoeff();
    scale_ = diag_max > 0 ? diag_max : 1.0;
    const SparseMatrix& A = p.constraints.A;
    const std::vector<int> reached = reached_columns(A);
    if (A.rows() > static_cast<Eigen::Index>(reached.size())) {
      // More rows than the unknowns they reach (a fine fixed region on a coarse level: on
      // the cow, 330k rows over 1k vertices) cannot be independent, and a KKT system that
      // size is slow to factor. With Ā = A on the reached unknowns, Ā P = Q R: a consistent
      // A x = C holds exactly when R₁ Pᵀ x = Q₁ᵀ C (the first rank(R) rows), which are
      // independent and as well conditioned as A.
      if (backend == Backend::Reference) compress_rows<ReferenceQR>(A, reached);
      else compress_rows<Eigen::SPQR<SparseMatrix>>(A, reached);
      factor(rows_);
      return;
    }
    factor(A);
    if (usable(A.rows(), p.g.cols())) return;
    const std::vector<int> keep = independent_rows(A, backend);
    if (keep.size() < static_cast<std::size_t>(A.rows())) {
      pick_t_ = row_picker(A.rows(), keep).transpose();
      dropped_ = A.rows() - static_cast<Eigen::Index>(keep.size());
      factor(pick_t_ * A);
      if (usable(A.rows(), p.g.cols())) return;  // targets are A's rows; K keeps the picked ones
    }
    // Nearly dependent rows (a fine fixed region two levels down) defeat the QR's rank test:
    // the kept rows leave the dropped ones violated. All rows then go into the regularized
    // [H Aᵀ; A −δI], nonsingular whatever the rows, penalizing the constraints with weight
    // s²/δ = 1e10·s, far above H's scale s.
    regularization_ = 1e-10 * scale_;
    pick_t_ = SparseMatrix();
    dropped_ = 0;
    factor(A);
  }

  EditSolution solve(const Eigen::MatrixXd& C) const {
    const Eigen::Index n = H_.rows();
    EditSolution out;
    Eigen::MatrixXd sol, rhs;
    const double residual = solve_system(C, sol, rhs);
    const std::string dropped = dropped_ ? std::to_string(dropped_) + " dependent constraint rows" : "";
    if (!(residual <= 1e-6)) {
      out.summary.message = "KKT system is singular (nothing pins the deformation?)";
      if (dropped_) out.summary.message.append(" after dropping ").append(dropped);
      out.delta = Eigen::MatrixXd::Zero(n, g_.cols());
      return out;
    }
    out.delta = sol.topRows(n);
    std::string note = dropped_ ? "dropped " + dropped : "";
    if (compressed_targets_) note = std::to_string(K_.rows() - n) + " independent constraint rows from a QR of the " + std::to_string(original_rows_);
    else if (regularization_ > 0) note.append(note.empty() ? "" : ", ").append("regularized (nearly dependent constraint rows)");
    out.summary = {Termination::Converged, 1, residual, note};
    out.constrained_vertices = static_cast<int>(K_.rows() - n);
    return out;
  }

 private:
  void factor(const SparseMatrix& A) {
    K_ = qp::lagrange_matrix(H_, A, scale_, regularization_);
    if (backend_ == Backend::Reference) lu_ = factored<Eigen::SparseLU<SparseMatrix>>(K_);
    else lu_ = factored<Eigen::UmfPackLU<SparseMatrix>>(K_);
  }

  template <class QR>
  void compress_rows(const SparseMatrix& A, const std::vector<int>& reached) {
    original_rows_ = A.rows();
    auto qr = std::make_unique<QR>();
    SparseMatrix on_reached = A * row_picker(A.cols(), reached);
    on_reached.makeCompressed();
    qr->compute(on_reached);
    if (qr->info() != Eigen::Success) throw SolverError("KKT: QR of the constraint rows failed");
    const Eigen::Index rank = qr->rank();
    const auto permutation = qr->colsPermutation();  // SPQR returns it by value: keep it alive
    const SparseMatrix R = SparseMatrix(qr->matrixR()).topRows(rank);
    Triplets t;
    for (int c = 0; c < R.outerSize(); ++c)
      for (SparseMatrix::InnerIterator it(R, c); it; ++it)
        t.emplace_back(static_cast<int>(it.row()), reached[permutation.indices()[c]], it.value());
    rows_.resize(rank, A.cols());
    rows_.setFromTriplets(t.begin(), t.end());
    // Q₁ᵀ = R₁₁⁻ᵀ (Ā P₁)ᵀ (P₁: the first rank columns of P), so a drag step pays one product
    // with Āᵀ and one sparse triangular solve instead of applying Q's Householder vectors.
    const SparseMatrix R11t = SparseMatrix(R.leftCols(rank)).transpose();
    std::vector<int> leading(static_cast<std::size_t>(rank));
    for (Eigen::Index k = 0; k < rank; ++k) leading[static_cast<std::size_t>(k)] = permutation.indices()[k];
    const SparseMatrix AP1 = on_reached * row_picker(on_reached.cols(), leading);
    if (backend_ == Backend::Reference) {
      const SparseMatrix AP1t = AP1.transpose();
      compressed_targets_ = [R11t, AP1t](const Eigen::MatrixXd& C) {
        const Eigen::MatrixXd y = AP1t * C;
        return Eigen::MatrixXd(R11t.triangularView<Eigen::Lower>().solve(y));
      };
    } else {  // one parallel pass over the (hundreds of thousands of) rows, every step of a drag
      const RowSparseMatrix AP1_rows(AP1);
      compressed_targets_ = [R11t, AP1_rows](const Eigen::MatrixXd& C) {
        RowBlock y;
        parallel_transpose_multiply(AP1_rows, RowBlock(C), y);
        return Eigen::MatrixXd(R11t.triangularView<Eigen::Lower>().solve(Eigen::MatrixXd(y)));
      };
    }
  }

  template <class LU>
  static std::function<bool(const Eigen::MatrixXd&, Eigen::MatrixXd&)> factored(const SparseMatrix& K) {
    auto lu = std::make_shared<LU>();
    // UMFPACK refines every solve by default (two more solves and products with K): ten times
    // the solve itself on the coarse KKT system of a drag. solve_system refines only when the
    // residual asks for it.
    if constexpr (std::is_same_v<LU, Eigen::UmfPackLU<SparseMatrix>>) lu->umfpackControl()(UMFPACK_IRSTEP) = 0;
    lu->compute(K);
    if (lu->info() != Eigen::Success) return {};
    return [lu](const Eigen::MatrixXd& rhs, Eigen::MatrixXd& x) {
      x = lu->solve(rhs);
      return lu->info() == Eigen::Success;
    };
  }

  // The relative residual of the solve (NaN when it failed). UMFPACK can "succeed" on a
  // numerically singular K and return huge values: the residual tells.
  double solve_system(const Eigen::MatrixXd& C, Eigen::MatrixXd& sol, Eigen::MatrixXd& rhs) const {
    const Eigen::Index n = H_.rows();
    rhs.resize(K_.rows(), g_.cols());
    rhs.topRows(n) = g_;
    if (compressed_targets_) rhs.bottomRows(K_.rows() - n) = scale_ * compressed_targets_(C);
    else rhs.bottomRows(K_.rows() - n) = scale_ * (pick_t_.size() ? Eigen::MatrixXd(pick_t_ * C) : C);
    if (!lu_ || !lu_(rhs, sol) || !sol.allFinite()) return std::numeric_limits<double>::quiet_NaN();
    double residual = relative_residual(K_, rhs, sol);
    for (int step = 0; step < kRefinementSteps && residual > kRefineAbove; ++step) {
      Eigen::MatrixXd correction;
      if (!lu_(Eigen::MatrixXd(rhs - K_ * sol), correction) || !correction.allFinite()) break;
      sol += correction;
      residual = relative_residual(K_, rhs, sol);
    }
    return residual;
  }
  static constexpr int kRefinementSteps = 2;
  static constexpr double kRefineAbove = 1e-13;

  // A random right-hand side: inconsistent for dependent rows, so their singularity shows.
  bool usable(Eigen::Index rows, Eigen::Index cols) const {
    std::mt19937 gen(11);
    std::uniform_real_distribution<double> d(-1, 1);
    Eigen::MatrixXd C(rows, cols), sol, rhs;
    for (Eigen::Index i = 0; i < C.size(); ++i) C.data()[i] = d(gen);
    return solve_system(C, sol, rhs) <= 1e-6;
  }

  const SparseMatrix& H_;
  const Eigen::MatrixXd& g_;
  Backend backend_;
  double scale_ = 1;
  SparseMatrix K_, pick_t_;  // pick_t_: the kept rows (empty: all)
  SparseMatrix rows_;        // R₁ Pᵀ on the full unknowns, when A's rows are compressed
  std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)> compressed_targets_;  // C ↦ Q₁ᵀ C
  Eigen::Index dropped_ = 0;
  double regularization_ = 0;  // δ of the regularized system (0: the exact Lagrange system)
  Eigen::Index original_rows_ = 0;
  std::function<bool(const Eigen::MatrixXd&, Eigen::MatrixXd&)> lu_;
};

namespace {

// Columns x, y, z stacked into one: an n × 3 matrix is, column-major, already [x; y; z].
Eigen::VectorXd stack(const Eigen::MatrixXd& M) { return Eigen::Map<const Eigen::VectorXd>(M.data(), M.size()); }
Eigen::MatrixXd unstack(const Eigen::MatrixXd& v) { return Eigen::Map<const Eigen::MatrixXd>(v.data(), v.size() / 3, 3); }

// The one coupled system of §5 on [Δx; Δy; Δz]: H three times on the diagonal, each point
// row three times, then the normal rows.
EditProblem stacked(const EditProblem& p) {
  const LinearConstraints& lc = p.constraints;
  EditProblem s;
  s.levels = p.levels;
  s.H = block_diagonal(p.H, 3);
  s.g = stack(p.g);
  const SparseMatrix A3 = block_diagonal(lc.A, 3);
  s.constraints.A = stack_rows({&A3, &lc.A_coupled});
  s.constraints.C = stacked_targets(lc, lc.C);
  return s;
}

void check_sizes(const EditProblem& p) {
  if (p.constraints.A.rows() == 0)
    throw InvalidInput(p.constraints.coupled()
                           ? "edit: normal constraints fix no position: add a point or fixed constraint"
                           : "edit: no constraint: the deformation is undetermined (add a point or fixed constraint)");
  if (p.H.rows() != p.H.cols() || p.g.rows() != p.H.rows() || p.constraints.A.cols() != p.H.rows() ||
      (p.constraints.coupled() && p.constraints.A_coupled.cols() != 3 * p.H.rows()))
    throw InvalidInput("edit: H, g and the constraints disagree in size");
}

}  // namespace

Eigen::MatrixXd stacked_targets(const LinearConstraints& lc, const Eigen::MatrixXd& C) {
  Eigen::MatrixXd out(3 * C.rows() + lc.C_coupled.rows(), 1);
  out << stack(C), lc.C_coupled;
  return out;
}

const NameTable<ConstraintMode>& constraint_mode_names() {
  static const NameTable<ConstraintMode> t{{ConstraintMode::Paper, "paper"},
                                           {ConstraintMode::Kkt, "kkt"},
                                           {ConstraintMode::QrPenalty, "qr_penalty"},
                                           {ConstraintMode::RangeSpace, "range_space"}};
  return t;
}

PreparedEdit::PreparedEdit(const EditProblem& p, ConstraintMode mode, Solver& solver, Backend backend)
    : solver_(solver) {
  Timer setup;
  check_sizes(p);
  original_ = &p;
  if (p.constraints.coupled()) stacked_ = stacked(p);
  const EditProblem& s = solved();
  if (mode == ConstraintMode::Kkt) {
    kkt_ = std::make_unique<KktFactorization>(s, backend);
    analyze_s_ = setup.seconds();
    return;
  }
  if (mode == ConstraintMode::QrPenalty || mode == ConstraintMode::RangeSpace) {
    Config defaults;
    const bool penalty = mode == ConstraintMode::QrPenalty;
    qp_ = qp::qp_solver_registry().create(penalty ? "qr_penalty" : "range_space", penalty ? backend : Backend::Optimized,
                                          defaults);
    qp_->analyze({s.H, s.g, s.constraints.A, Eigen::MatrixXd::Zero(s.constraints.A.rows(), s.g.cols()), {}});
    analyze_s_ = setup.seconds();
    return;
  }
  touched_ = reached_columns(s.constraints.A);
  ls_ = std::make_unique<MinNormLeastSquares>(s.constraints.A * row_picker(s.constraints.A.cols(), touched_), backend);
  red_ = reduce({s.H, s.g, touched_, Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(touched_.size()), s.g.cols())});
  if (!red_.free.empty()) {
    if (solver.uses_levels()) {
      if (!s.levels) throw InvalidInput("edit: a multilevel solver needs a hierarchy below the edit level");
      // The solver sees the reduced system: its finest unknowns are the free vertices.
      solver.set_levels(s.levels, {red_.free, static_cast<int>(s.H.rows() / s.levels->prolongation.back().rows())});
    }
    solver.analyze(red_.A);
  }
  analyze_s_ = setup.seconds();
}

PreparedEdit::~PreparedEdit() = default;

EditSolution PreparedEdit::solve(const Eigen::MatrixXd& C, const IterationCallback& cb, const Eigen::MatrixXd* initial,
                                 ConstrainedStart constrained) {
  const EditProblem& s = solved();
  const bool coupled = stacked_.has_value();
  const Eigen::MatrixXd targets = coupled ? stacked_targets(original_->constraints, C) : C;
  const Eigen::MatrixXd start = initial ? (coupled ? Eigen::MatrixXd(stack(*initial)) : *initial) : Eigen::MatrixXd();
  EditSolution out;
  if (kkt_) {
    Timer t;
    out = kkt_->solve(targets);
    out.solve_s = t.seconds();
  } else if (qp_) {
    Timer t;
    const qp::QpReport r = qp_->solve(s.g, targets);
    out.delta = r.p;
    out.summary = {r.termination, 1, -1, r.message};
    out.solve_s = t.seconds();
  } else {
    out = solve_paper(targets, initial ? &start : nullptr, constrained, cb);
  }
  out.analyze_s = analyze_s_;
  out.constraint_residual = measure_constraints_ ? (s.constraints.A * out.delta - targets).norm()
                                                 : std::numeric_limits<double>::quiet_NaN();
  if (coupled) out.delta = unstack(out.delta);
  return out;
}

double PreparedEdit::constraint_residual(const Eigen::MatrixXd& delta, const Eigen::MatrixXd& C) const {
  if (!stacked_) return (original_->constraints.A * delta - C).norm();
  return (stacked_->constraints.A * stack(delta) - stacked_targets(original_->constraints, C)).norm();
}

EditSolution PreparedEdit::solve_paper(const Eigen::MatrixXd& targets, const Eigen::MatrixXd* start,
                                       ConstrainedStart constrained, const IterationCallback& cb) {
  const EditProblem& s = solved();
  const bool coupled = stacked_.has_value();
  // Minimum norm: the paper's A⁺C. Nearest to the start: start + A⁺(C − A·start), the
  // smallest change that satisfies the rows (a prolongated coarse solution keeps its shape).
  Eigen::MatrixXd fixed;
  if (constrained == ConstrainedStart::NearestToInitial && start) {
    Eigen::MatrixXd on_touched(static_cast<Eigen::Index>(touched_.size()), start->cols());
    for (std::size_t k = 0; k < touched_.size(); ++k) on_touched.row(static_cast<Eigen::Index>(k)) = start->row(touched_[k]);
    fixed = on_touched + ls_->solve(targets - s.constraints.A * *start).X;
  } else {
    fixed = ls_->solve(targets).X;
  }
  red_.set_fixed_values(fixed);
  EditSolution out;
  out.constrained_vertices = static_cast<int>(touched_.size());
  Eigen::MatrixXd x = start ? red_.restrict_to_free(*start)
                            : Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(red_.free.size()), s.g.cols());
  if (red_.free.empty()) {
    out.summary = {Termination::Converged, 0, 0.0, "every vertex is constrained"};
  } else {
    // Callers see the whole n × 3 deformation, not the solver's reduced unknowns. The
    // reduced energy differs from the full one by a constant (the fixed vertices' part):
    // measured once, so a check costs no product with the full H.
    Eigen::MatrixXd full;
    std::optional<double> energy_offset;
    const IterationCallback expanded = [&](const IterationRecord& r) {
      full = red_.expand(*r.x);
      if (coupled) full = unstack(full);
      if (!std::isnan(r.energy) && !energy_offset)
        energy_offset = quadratic_energy(original_->H, original_->g, full) - r.energy;
      return cb({r.iteration, r.residual, r.seconds, r.energy + energy_offset.value_or(0.0), &full});
    };
    Timer t;
    out.summary = solver_.solve(red_.A, red_.b, x, cb ? expanded : IterationCallback());
    out.solve_s = t.seconds() - out.summary.observe_s;
  }
  out.delta = red_.expand(x);
  return out;
}

EditSolution solve_edit(const EditProblem& p, ConstraintMode mode, Solver& free_solver, Backend backend,
                        const IterationCallback& cb, const Eigen::MatrixXd* initial) {
  return PreparedEdit(p, mode, free_solver, backend).solve(p.constraints.C, cb, initial);
}

}  // namespace fairshape
