// The Lagrange augmented system of Welch & Witkin eq. 9,
//   [H   sĀᵀ] [p]   [ f  ]
//   [sĀ   0 ] [y] = [s b̄],
// over Ā p = b̄, a maximal independent subset of the constraint rows (§4.3), chosen by a
// rank-revealing QR of Aᵀ, or, when A has more rows than the unknowns it reaches, reduced
// orthogonally at once (the policy of qp/row_dependence.h). When the kept rows are still too close to
// dependent for the LU, or the dropped rows disagree with the kept ones, the rows are reduced
// instead to Ā = R₁Pᵀ, b̄ = Q₁ᵀ b from A P = Q R: well conditioned, and for inconsistent targets
// the least-squares fit (the paper's AᵀA p = Aᵀb, without squaring A's condition number),
// reported with its residual. Scaled by s = max diag H so the LU keeps its digits; when that
// system still looks singular it is equilibrated symmetrically (Ruiz: D K D with every row's
// largest entry near 1) and factored again, so the verdict does not depend on how far H's
// diagonal spreads — 8 orders on a dense scan under one subdivision level, where the LU called
// a well-posed edit singular. (Not always: on well-scaled systems the plain one's answers are
// the more exact, e.g. the rotation-aware rounds' energies on the cow.) When even the
// equilibrated system looks singular, the unknowns that rows of their own pin (held vertices)
// are eliminated and the smaller program, whose H is then positive definite, is solved by the
// range-space method (pinned_reduction.h) — the same minimizer. Optimized:
// UMFPACK (symmetric strategy), whose symbolic analysis is reused while the pattern stays the
// same; reference: Eigen SparseLU.
#include <Eigen/SparseLU>
#include <Eigen/UmfPackSupport>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>

#include "fairshape/core/error.h"
#include "fairshape/core/message_format.h"
#include "fairshape/core/timer.h"
#include "fairshape/problem/least_squares.h"
#include "fairshape/qp/same_matrix.h"
#include "fairshape/qp/kkt_solver.h"
#include "fairshape/qp/constraint_policy.h"
#include "fairshape/qp/pinned_reduction.h"
#include "fairshape/qp/range_space_solver.h"

namespace fairshape::qp {

class LuFactor {
 public:
  virtual ~LuFactor() = default;
  virtual bool factor(const SparseMatrix& K) = 0;
  virtual Eigen::MatrixXd solve(const Eigen::MatrixXd& rhs) const = 0;
  //! Symbolic analyses done so far (the reference redoes it with every factorization).
  virtual int analyses() const = 0;
};

namespace {

class ReferenceLu final : public LuFactor {
 public:
  bool factor(const SparseMatrix& K) override {
    lu_.compute(K);
    ++analyses_;
    return lu_.info() == Eigen::Success;
  }
  int analyses() const override { return analyses_; }
  Eigen::MatrixXd solve(const Eigen::MatrixXd& rhs) const override {
    return const_cast<Eigen::SparseLU<SparseMatrix>&>(lu_).solve(rhs);
  }

 private:
  Eigen::SparseLU<SparseMatrix> lu_;
  int analyses_ = 0;
};

// UMFPACK with the symbolic analysis kept across factorizations of the same pattern.
class UmfpackLu final : public LuFactor {
 public:
  UmfpackLu() {
    // The Lagrange matrix is structurally symmetric: the symmetric strategy orders it like a
    // Cholesky factor (the unsymmetric default filled it 10x); refinement is done by the caller.
    lu_.umfpackControl()(UMFPACK_STRATEGY) = UMFPACK_STRATEGY_SYMMETRIC;
    lu_.umfpackControl()(UMFPACK_IRSTEP) = 0;
  }
  bool factor(const SparseMatrix& K) override {
    if (!same_pattern(K)) {
      lu_.analyzePattern(K);
      outer_.assign(K.outerIndexPtr(), K.outerIndexPtr() + K.outerSize() + 1);
      inner_.assign(K.innerIndexPtr(), K.innerIndexPtr() + K.nonZeros());
      ++analyses_;
    }
    lu_.factorize(K);
    return lu_.info() == Eigen::Success;
  }
  Eigen::MatrixXd solve(const Eigen::MatrixXd& rhs) const override { return lu_.solve(rhs); }
  int analyses() const override { return analyses_; }

 private:
  bool same_pattern(const SparseMatrix& K) const {
    return static_cast<Eigen::Index>(outer_.size()) == K.outerSize() + 1 &&
           std::equal(outer_.begin(), outer_.end(), K.outerIndexPtr()) &&
           static_cast<Eigen::Index>(inner_.size()) == K.nonZeros() &&
           std::equal(inner_.begin(), inner_.end(), K.innerIndexPtr());
  }
  Eigen::UmfPackLU<SparseMatrix> lu_;
  std::vector<int> outer_, inner_;
  int analyses_ = 0;
};


// Iterative refinement: the Lagrange system is indefinite and, with nearly dependent curve
// rows, badly conditioned; corrections with the same factors recover the digits the pivoting LU
// loses — while they shrink the residual, at most three.
Eigen::MatrixXd refined_solve(const LuFactor& lu, const SparseMatrix& K, const Eigen::MatrixXd& rhs) {
  Eigen::MatrixXd x = lu.solve(rhs);
  if (!x.allFinite()) return x;
  Eigen::MatrixXd r = rhs - K * x;
  double before = r.norm();
  for (int step = 0; step < 3 && before > 1e-14 * rhs.norm(); ++step) {
    const Eigen::MatrixXd corrected = x + lu.solve(r);
    Eigen::MatrixXd r_corrected = rhs - K * corrected;
    const double after = r_corrected.norm();
    if (!(after < before)) break;
    x = corrected;
    r = std::move(r_corrected);
    before = after;
  }
  return x;
}

// Ruiz's symmetric equilibration of K in place: D such that D K D has rows (and, K being
// symmetric, columns) whose largest magnitude is within 10 % of 1. Each sweep is one pass over the
// nonzeros; a few suffice. An empty row keeps its scale 1.
Eigen::VectorXd equilibrate(SparseMatrix& K) {
  Eigen::VectorXd d = Eigen::VectorXd::Ones(K.cols());
  for (int sweep = 0; sweep < 20; ++sweep) {
    Eigen::VectorXd largest = Eigen::VectorXd::Zero(K.cols());
    for (int c = 0; c < K.outerSize(); ++c)
      for (SparseMatrix::InnerIterator it(K, c); it; ++it) largest[c] = std::max(largest[c], std::abs(it.value()));
    if (((largest.array() - 1).abs() <= 0.1 || largest.array() == 0).all()) break;
    const Eigen::VectorXd s = (largest.array() > 0).select(largest.array().sqrt().inverse(), 1.0);
    for (int c = 0; c < K.outerSize(); ++c)
      for (SparseMatrix::InnerIterator it(K, c); it; ++it) it.valueRef() *= s[it.row()] * s[c];
    d.array() *= s.array();
  }
  return d;
}

}  // namespace

SparseMatrix lagrange_matrix(const SparseMatrix& H, const SparseMatrix& A, double scale, double regularization) {
  const Eigen::Index n = H.rows(), m = A.rows();
  Triplets t;
  t.reserve(static_cast<std::size_t>(H.nonZeros() + 2 * A.nonZeros() + (regularization > 0 ? m : 0)));
  for (int c = 0; c < H.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(H, c); it; ++it) t.emplace_back(static_cast<int>(it.row()), c, it.value());
  for (int c = 0; c < A.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(A, c); it; ++it) {
      t.emplace_back(static_cast<int>(n + it.row()), c, scale * it.value());
      t.emplace_back(c, static_cast<int>(n + it.row()), scale * it.value());
    }
  if (regularization > 0)
    for (Eigen::Index i = 0; i < m; ++i) t.emplace_back(static_cast<int>(n + i), static_cast<int>(n + i), -regularization);
  SparseMatrix K(n + m, n + m);
  K.setFromTriplets(t.begin(), t.end());
  K.makeCompressed();
  return K;
}

// The factored Lagrange system over the compressed constraint rows.
struct KktSolver::System {
  CompressedRows rows;
  SparseMatrix K;     // [H sĀᵀ; sĀ 0], or D [H sĀᵀ; sĀ 0] D when equilibrated: the factored matrix
  Eigen::VectorXd D;  // the equilibration (empty: none): K x = D r  ⇔  [H sĀᵀ; sĀ 0] (D x) = r
  std::unique_ptr<LuFactor> lu;
  bool singular = false;
};

KktSolver::KktSolver(Backend backend, ConstraintPolicy policy, bool reuse) : backend_(backend), policy_(policy), reuse_(reuse) {
  require_backend(backend);
}
KktSolver::~KktSolver() = default;

namespace {

// Factors K and probes it: UMFPACK may "succeed" on a numerically singular matrix, so a random
// right-hand side (inconsistent for a singular K, its residual then of the order of the
// right-hand side) decides. True when K is nonsingular.
bool factor_nonsingular(LuFactor& lu, const SparseMatrix& K) {
  if (!lu.factor(K)) return false;
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> d(-1, 1);
  Eigen::VectorXd probe(K.rows());
  for (Eigen::Index i = 0; i < probe.size(); ++i) probe[i] = d(gen);
  const Eigen::VectorXd x = refined_solve(lu, K, probe);
  return x.allFinite() && (K * x - probe).norm() <= 1e-6 * probe.norm();
}

}  // namespace

std::unique_ptr<KktSolver::System> KktSolver::build(CompressedRows rows, std::unique_ptr<LuFactor> recycled) {
  ++factorizations_;
  auto sys = std::make_unique<System>();
  sys->rows = std::move(rows);
  sys->K = lagrange_matrix(H_, sys->rows.rows, scale_);
  if (recycled) sys->lu = std::move(recycled);  // keeps UMFPACK's symbolic analysis when the pattern repeats
  else if (backend_ == Backend::Reference) sys->lu = std::make_unique<ReferenceLu>();
  else sys->lu = std::make_unique<UmfpackLu>();
  sys->singular = !factor_nonsingular(*sys->lu, sys->K);
  if (sys->singular) {  // perhaps only badly scaled: equilibrated, the same pattern factored again
    sys->D = equilibrate(sys->K);
    sys->singular = !factor_nonsingular(*sys->lu, sys->K);
  }
  return sys;
}

void KktSolver::analyze(const QuadraticProgram& qp) {
  validate(qp);
  const Timer timer;
  // Everything analyze() derives (dropped rows, the factored system, the conditioning) depends
  // on H and A only: a step that keeps both keeps it, and solve() takes the new f and b.
  reused_ = reuse_ && main_ && same_matrix(qp.hessian(), H_) && same_matrix(qp.A, A_original_);
  if (reused_) {
    analyze_s_ = timer.seconds();
    return;
  }
  H_ = qp.hessian();
  A_original_ = qp.A;
  scaling_ = scale_rows(qp.A);  // unit rows: one meaning of "dependent" for every kind of row
  A_ = scaling_.scaled;
  const double diag = H_.rows() ? H_.diagonal().cwiseAbs().maxCoeff() : 0.0;
  scale_ = diag > 0 ? diag : 1.0;
  least_squares_.reset();
  CompressedRows rows = without_dependent_rows(A_, backend_, policy_.rank_tolerance);
  reduced_ = rows.orthogonal;
  const bool dropped = rows.rows.rows() < A_.rows();
  main_ = build(std::move(rows), main_ ? std::move(main_->lu) : nullptr);
  if (main_->singular && dropped && !reduced_) {
    // The kept original rows are still nearly dependent (curve rows along a curved path): the
    // orthogonal reduction R₁Pᵀ is well conditioned where a subset of the rows is not.
    main_ = build(compress_rows(A_, backend_, policy_.rank_tolerance), nullptr);
    reduced_ = true;
  }
  conditioning_ = constraint_conditioning(H_, A_, policy_.rank_tolerance);
  prepare_pinned_fallback();
  analyze_s_ = timer.seconds();
}

void KktSolver::prepare_pinned_fallback() {
  pinned_.reset();
  pinned_solver_.reset();
  if (!main_->singular) return;
  auto reduction = std::make_unique<PinnedReduction>(H_, A_original_);
  if (!reduction->any() || reduction->free_rows().rows() > RangeSpaceSolver::kMaxRows) return;
  QuadraticProgram reduced;
  reduced.H = reduction->free_hessian();
  reduced.A = reduction->free_rows();
  reduced.f = Eigen::MatrixXd::Zero(reduced.H.rows(), 1);
  reduced.b = Eigen::MatrixXd::Zero(reduced.A.rows(), 1);
  pinned_solver_ = std::make_unique<RangeSpaceSolver>(policy_);
  pinned_solver_->analyze(reduced);
  pinned_ = std::move(reduction);
}

QpReport KktSolver::solve_pinned(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b) {
  const Eigen::MatrixXd f_free = pinned_->reduced_f(f, b), b_free = pinned_->reduced_b(b);
  QpReport out = pinned_solver_->solve(f_free, b_free);
  // Iterative refinement: the correction δ of p minimizes ½δᵀHδ − δᵀ(f − Hp) subject to
  // Aδ = b − Ap, the same program with the residuals as right-hand sides. H_FF spans as many
  // orders as H's diagonal did, so one solve leaves digits that the next ones recover.
  for (int step = 0; step < 2 && out.summary.termination == Termination::Converged && out.p.allFinite(); ++step) {
    const SparseMatrix& H = pinned_->free_hessian();
    const SparseMatrix& A = pinned_->free_rows();
    const QpReport correction = pinned_solver_->solve(f_free - H * out.p, b_free - A * out.p);
    if (correction.summary.termination != Termination::Converged || !correction.p.allFinite()) break;
    out.p += correction.p;
  }
  out.p = out.p.allFinite() && out.p.size() ? pinned_->expand(out.p, b) : Eigen::MatrixXd::Zero(H_.rows(), f.cols());
  const std::string note = "the Lagrange system looked singular, also equilibrated: " + std::to_string(pinned_->n_pinned()) +
                           " unknowns pinned by rows of their own eliminated, the rest solved by the range-space method";
  out.summary.message = out.summary.message.empty() ? note : note + "; " + out.summary.message;
  // Judged on the original program: every row, the pinning ones included.
  assess(out, {H_, f, A_original_, b, scaling_, conditioning_}, policy_);
  return out;
}

int KktSolver::symbolic_analyses() const { return main_ ? main_->lu->analyses() : 0; }

QpReport KktSolver::solve_with(const System& sys, const Eigen::MatrixXd& f, const Eigen::MatrixXd& b) const {
  QpReport out;
  const Eigen::Index n = H_.rows();
  out.dropped_rows = static_cast<int>(A_.rows() - sys.rows.rows.rows());
  if (sys.singular) {
    out.p = Eigen::MatrixXd::Zero(n, f.cols());
    out.summary.message = "KKT system is singular: the constraints do not pin the energy's null space";
    return out;
  }
  Eigen::MatrixXd rhs(sys.K.rows(), f.cols());
  rhs.topRows(n) = f;
  rhs.bottomRows(sys.K.rows() - n) = scale_ * sys.rows.targets(b);
  const Eigen::MatrixXd x =
      sys.D.size() ? Eigen::MatrixXd(sys.D.asDiagonal() * refined_solve(*sys.lu, sys.K, sys.D.asDiagonal() * rhs))
                   : refined_solve(*sys.lu, sys.K, rhs);
  if (!x.allFinite()) {
    out.p = Eigen::MatrixXd::Zero(n, f.cols());
    out.summary.message = "KKT solve produced non-finite values";
    return out;
  }
  out.p = x.topRows(n);
  out.summary.termination = Termination::Converged;
  out.summary.iterations = 1;  // one direct solve
  return out;
}

QpReport KktSolver::solve(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b) {
  FAIRSHAPE_ASSERT(main_, "KktSolver::solve before analyze");
  if (f.rows() != H_.rows() || b.rows() != A_.rows() || (b.rows() && b.cols() != f.cols()))
    throw InvalidInput("KKT solve: right-hand sides do not match the analyzed program");
  if (main_->singular && pinned_solver_) return solve_pinned(f, b);
  const Eigen::MatrixXd unit_b = scaling_.d.asDiagonal() * b;
  QpReport out = solve_with(*main_, f, unit_b);
  if (out.summary.termination == Termination::Converged && out.dropped_rows > 0 && !reduced_ &&
      relative_unit_residual(A_ * out.p, unit_b) > policy_.constraint_tolerance) {
    // The dropped rows disagree with the kept ones: fit all of them in the least-squares sense.
    if (!least_squares_) least_squares_ = build(compress_rows(A_, backend_, policy_.rank_tolerance), nullptr);
    const int dropped = out.dropped_rows;
    out = solve_with(*least_squares_, f, unit_b);
    out.dropped_rows = dropped;
    if (out.summary.termination == Termination::Converged) out.summary.message = "least-squares fit of all rows";
  }
  if (main_->D.size() && out.summary.termination == Termination::Converged) {
    const std::string note = "equilibrated: the plain Lagrange system looked singular";
    out.summary.message = out.summary.message.empty() ? note : out.summary.message + "; " + note;
  }
  if (out.dropped_rows) {
    const std::string note = "dropped " + std::to_string(out.dropped_rows) + " dependent constraint rows (rank_tolerance " +
                             sci(policy_.rank_tolerance) + ")";
    out.summary.message = out.summary.message.empty() ? note : out.summary.message + "; " + note;
  }
  assess(out, {H_, f, A_original_, b, scaling_, conditioning_}, policy_);
  return out;
}

}  // namespace fairshape::qp
