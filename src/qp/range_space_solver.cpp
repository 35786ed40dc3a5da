#include "fairshape/qp/range_space_solver.h"
#include "fairshape/qp/same_matrix.h"

#include "fairshape/qp/kkt_solver.h"
#include "fairshape/qp/qr_penalty_solver.h"
#include "fairshape/qp/constraint_policy.h"
#include "fairshape/qp/row_dependence.h"

#include <Eigen/CholmodSupport>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include <algorithm>
#include <limits>
#include <map>
#include <cmath>
#include <string>

#include "fairshape/core/error.h"
#include "fairshape/core/message_format.h"
#include "fairshape/core/timer.h"
#include "fairshape/problem/constrained_system.h"
#include "fairshape/problem/least_squares.h"

namespace fairshape::qp {

struct RangeSpaceSolver::Cholmod {
  cholmod_common common;
  cholmod_factor* factor = nullptr;
  Cholmod() {
    cholmod_start(&common);
    common.supernodal = CHOLMOD_SIMPLICIAL;  // cholmod_updown works on simplicial LDLᵀ
    common.final_ll = 0;
  }
  ~Cholmod() {
    if (factor) cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }
};

RangeSpaceSolver::RangeSpaceSolver(ConstraintPolicy policy) : chol_(std::make_unique<Cholmod>()), policy_(policy) {}
RangeSpaceSolver::~RangeSpaceSolver() = default;

namespace {
using RowKey = std::vector<std::pair<int, double>>;
std::vector<RowKey> row_keys(const SparseMatrix& A) {
  std::vector<RowKey> keys(static_cast<std::size_t>(A.rows()));
  for (int c = 0; c < A.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(A, c); it; ++it) keys[static_cast<std::size_t>(it.row())].emplace_back(c, it.value());
  return keys;
}
}  // namespace

bool RangeSpaceSolver::update_rows(const SparseMatrix& A) {
  if (!chol_->factor || singular_ || A.rows() == 0 || A_.rows() == 0) return false;
  // Match the new rows with the current ones (bit-identical: an unchanged constraint assembles
  // the same row); the others are removed (a downdate) or bordered on.
  const std::vector<RowKey> now = row_keys(A_original_), next = row_keys(A);
  std::map<RowKey, std::vector<int>> unused;
  for (int r = static_cast<int>(now.size()) - 1; r >= 0; --r) unused[now[static_cast<std::size_t>(r)]].push_back(r);
  std::vector<int> match(next.size(), -1), added;
  for (std::size_t i = 0; i < next.size(); ++i) {
    auto it = unused.find(next[i]);
    if (it == unused.end() || it->second.empty()) {
      added.push_back(static_cast<int>(i));
      continue;
    }
    match[i] = it->second.back();
    it->second.pop_back();
  }
  std::vector<int> removed;
  for (const auto& [key, rows] : unused) removed.insert(removed.end(), rows.begin(), rows.end());
  if (removed.size() + added.size() > next.size()) return false;  // mostly new rows: refactoring is as cheap
  try {
    if (!removed.empty()) remove_rows(removed);
  } catch (const SolverError&) {
    return false;
  }
  if (!factor_positive_definite()) return false;  // the removed rows pinned what the others do not
  if (!added.empty()) add_rows(SparseMatrix(row_picker(A.rows(), added).transpose()) * A);
  // The solver's row order now: the kept rows in their old order, then the added ones.
  std::vector<int> kept_position(now.size(), -1);
  std::sort(removed.begin(), removed.end());
  for (int r = 0, k = 0, gone = 0; r < static_cast<int>(now.size()); ++r) {
    if (gone < static_cast<int>(removed.size()) && removed[gone] == r) {
      ++gone;
      continue;
    }
    kept_position[static_cast<std::size_t>(r)] = k++;
  }
  const int kept = static_cast<int>(now.size() - removed.size());
  order_.assign(next.size(), -1);
  for (std::size_t i = 0; i < next.size(); ++i)
    if (match[i] >= 0) order_[static_cast<std::size_t>(kept_position[static_cast<std::size_t>(match[i])])] = static_cast<int>(i);
  for (std::size_t j = 0; j < added.size(); ++j) order_[static_cast<std::size_t>(kept) + j] = added[j];
  last_update_ = {static_cast<int>(added.size()), static_cast<int>(removed.size())};
  return true;
}

bool RangeSpaceSolver::factor_positive_definite() const {
  const cholmod_factor* L = chol_->factor;
  if (!L || L->is_super || L->is_ll) return L != nullptr;
  // Simplicial LDLᵀ: each column starts with its D entry.
  const auto* p = static_cast<const int*>(L->p);
  const auto* x = static_cast<const double*>(L->x);
  double largest = 0, smallest = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < L->n; ++j) {
    largest = std::max(largest, x[p[j]]);
    smallest = std::min(smallest, x[p[j]]);
  }
  return smallest > 1e-12 * largest;
}

void RangeSpaceSolver::analyze(const QuadraticProgram& qp) {
  validate(qp);
  if (qp.A.rows() > kMaxRows)
    throw InvalidInput("range_space: " + std::to_string(qp.A.rows()) + " constraint rows are too many for its dense Schur complement (at most " +
                       std::to_string(kMaxRows) + "); use kkt or qr_penalty");
  const Timer timer;
  // Same energy, changed constraints (a design step): update the factor instead of refactoring.
  if (same_matrix(qp.hessian(), H_) && update_rows(qp.A)) {
    analyze_s_ = timer.seconds();
    return;
  }
  last_update_.reset();
  order_.clear();
  H_ = qp.hessian();
  A_original_ = qp.A;
  scaling_ = scale_rows(qp.A);  // unit rows: one meaning of "dependent" for every kind of row
  A_ = scaling_.scaled;
  const SparseMatrix AtA = SparseMatrix(A_.transpose()) * A_;
  rho_ = schur_rho(H_, A_);
  in_factor_.assign(static_cast<std::size_t>(A_.rows()), 1);
  SparseMatrix Hr = H_ + rho_ * AtA;
  Hr.makeCompressed();
  auto& c = *chol_;
  if (c.factor) cholmod_free_factor(&c.factor, &c.common);
  cholmod_sparse view = Eigen::viewAsCholmod(Hr);
  view.stype = -1;  // symmetric, lower triangle used
  c.factor = cholmod_analyze(&view, &c.common);
  singular_ = !c.factor || !cholmod_factorize(&view, c.factor, &c.common) || c.common.status == CHOLMOD_NOT_POSDEF;
  if (!singular_) rebuild_schur();
  analyze_s_ = timer.seconds();
}

Eigen::MatrixXd RangeSpaceSolver::solve_h(const Eigen::MatrixXd& rhs) const {
  Eigen::MatrixXd copy = rhs;
  cholmod_dense b = Eigen::viewAsCholmod(copy);
  cholmod_dense* x = cholmod_solve(CHOLMOD_A, chol_->factor, &b, &chol_->common);
  if (!x) throw SolverError("range-space: CHOLMOD solve failed");
  Eigen::MatrixXd out = Eigen::Map<Eigen::MatrixXd>(static_cast<double*>(x->x), rhs.rows(), rhs.cols());
  cholmod_free_dense(&x, &chol_->common);
  return out;
}

void RangeSpaceSolver::rebuild_schur() {
  if (A_.rows() == 0) {
    Z_.resize(H_.rows(), 0);
    S_.resize(0, 0);
    return;
  }
  Z_ = solve_h(Eigen::MatrixXd(SparseMatrix(A_.transpose())));
  S_ = A_ * Z_;
  decompose_schur();
}

void RangeSpaceSolver::decompose_schur() {
  // The rank policy (qp/constraint_policy.h) decides on A itself; S = A H⁻¹ Aᵀ squares A's
  // singular values, so its eigenvalues below the square of the tolerance are rounding noise.
  int rank = row_rank(A_, policy_.rank_tolerance);
  if (rank < 0) {  // too large for the dense rank test: S's own spectrum at the squared tolerance
    const Eigen::VectorXd l = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S_, Eigen::EigenvaluesOnly).eigenvalues();
    rank = static_cast<int>((l.array() > policy_.rank_tolerance * policy_.rank_tolerance * l.maxCoeff()).count());
  }
  conditioning_.spectrum = schur_spectrum(S_, rank);
  conditioning_.rho = rho_;
  conditioning_.estimated = true;
}

void RangeSpaceSolver::updown(bool update, const SparseMatrix& rows) {
  // cholmod_updown wants C permuted like the factor: C = P (√ρ rowsᵀ).
  SparseMatrix C = std::sqrt(rho_) * SparseMatrix(rows.transpose());
  C.makeCompressed();
  auto& c = *chol_;
  cholmod_sparse view = Eigen::viewAsCholmod(C);
  cholmod_sparse* permuted = cholmod_submatrix(&view, static_cast<int*>(c.factor->Perm), static_cast<long>(c.factor->n),
                                               nullptr, -1, 1, 1, &c.common);
  const int ok = cholmod_updown(update ? 1 : 0, permuted, c.factor, &c.common);
  cholmod_free_sparse(&permuted, &c.common);
  if (!ok) throw SolverError("range-space: CHOLMOD update/downdate failed");
}

void RangeSpaceSolver::add_rows(const SparseMatrix& original_rows) {
  if (original_rows.cols() != H_.cols())
    throw InvalidInput("range-space: new constraint rows have " + std::to_string(original_rows.cols()) + " columns, expected " +
                       std::to_string(H_.cols()));
  FAIRSHAPE_ASSERT(!singular_, "range-space: add_rows on a singular system");
  order_.clear();  // b comes in the solver's own order (update_rows sets it afterwards)
  const RowScaling added = scale_rows(original_rows);
  const SparseMatrix& rows = added.scaled;
  A_original_ = stack_rows({&A_original_, &original_rows});
  Eigen::VectorXd d(scaling_.d.size() + added.d.size());
  d << scaling_.d, added.d;
  scaling_.d = std::move(d);
  scaling_.zero_rows += added.zero_rows;
  // H_ρ is already positive definite, so new rows need not enter it: only S is bordered,
  // [S, A Z_C; C Z, C Z_C] with Z_C = H_ρ⁻¹Cᵀ (one solve per new row), and re-decomposed.
  const Eigen::MatrixXd Zc = solve_h(Eigen::MatrixXd(SparseMatrix(rows.transpose())));
  const Eigen::Index m = A_.rows(), k = rows.rows();
  Eigen::MatrixXd S(m + k, m + k);
  S.topLeftCorner(m, m) = S_;
  S.topRightCorner(m, k) = A_ * Zc;
  S.bottomLeftCorner(k, m) = rows * Z_;
  S.bottomRightCorner(k, k) = rows * Zc;
  S_ = std::move(S);
  Eigen::MatrixXd Z(Z_.rows(), m + k);
  Z << Z_, Zc;
  Z_ = std::move(Z);
  A_ = stack_rows({&A_, &rows});
  in_factor_.resize(static_cast<std::size_t>(m + k), 0);
  decompose_schur();
}

void RangeSpaceSolver::remove_rows(std::vector<int> rows) {
  order_.clear();  // b comes in the solver's own order (update_rows sets it afterwards)
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  for (int r : rows)
    if (r < 0 || r >= A_.rows()) throw InvalidInput("range-space: no constraint row " + std::to_string(r));
  std::vector<int> keep, factored;
  for (int r = 0, k = 0; r < A_.rows(); ++r) {
    if (k < static_cast<int>(rows.size()) && rows[k] == r) {
      ++k;
      if (in_factor_[r]) factored.push_back(r);
    } else {
      keep.push_back(r);
    }
  }
  const SparseMatrix keep_t = SparseMatrix(row_picker(A_.rows(), keep).transpose());
  A_original_ = keep_t * A_original_;
  scaling_.d = Eigen::VectorXd(keep_t * scaling_.d);
  std::vector<char> in_factor;
  for (int r : keep) in_factor.push_back(in_factor_[r]);
  in_factor_ = std::move(in_factor);
  if (!factored.empty()) {
    // Rows that are part of H_ρ leave it by a downdate; H_ρ⁻¹ changed, so S is rebuilt.
    updown(false, SparseMatrix(row_picker(A_.rows(), factored).transpose()) * A_);
    A_ = keep_t * A_;
    rebuild_schur();
    return;
  }
  // Rows added by bordering: drop their rows and columns of S and Z.
  Eigen::MatrixXd S(keep.size(), keep.size()), Z(Z_.rows(), keep.size());
  for (std::size_t i = 0; i < keep.size(); ++i) {
    Z.col(i) = Z_.col(keep[i]);
    for (std::size_t j = 0; j < keep.size(); ++j) S(i, j) = S_(keep[i], keep[j]);
  }
  S_ = std::move(S);
  Z_ = std::move(Z);
  A_ = keep_t * A_;
  decompose_schur();
}

QpReport RangeSpaceSolver::solve(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b_original) {
  if (f.rows() != H_.rows() || b_original.rows() != A_.rows() || (b_original.rows() && b_original.cols() != f.cols()))
    throw InvalidInput("range-space solve: right-hand sides do not match the analyzed program");
  QpReport out;
  if (singular_) {
    out.p = Eigen::MatrixXd::Zero(H_.rows(), f.cols());
    out.summary.message = "H + rho AᵀA is not positive definite: the constraints do not pin the energy's null space";
    return out;
  }
  // The caller's rows in the solver's order (after updates: kept rows, then the added ones).
  Eigen::MatrixXd ordered = b_original;
  for (std::size_t i = 0; i < order_.size(); ++i) ordered.row(static_cast<Eigen::Index>(i)) = b_original.row(order_[i]);
  const Eigen::MatrixXd b = scaling_.d.asDiagonal() * ordered;
  // g = f + ρ A_Fᵀ b_F over the rows that are part of H_ρ (the augmented Lagrangian's term).
  Eigen::MatrixXd bf = b;
  for (Eigen::Index r = 0; r < bf.rows(); ++r)
    if (!in_factor_[static_cast<std::size_t>(r)]) bf.row(r).setZero();
  const Eigen::MatrixXd g = A_.rows() ? Eigen::MatrixXd(f + rho_ * (SparseMatrix(A_.transpose()) * bf)) : f;
  const Eigen::MatrixXd y = solve_h(g);
  out.p = y;
  if (A_.rows()) {
    const Eigen::MatrixXd lambda = conditioning_.spectrum.solve(Eigen::MatrixXd(A_ * y - b));
    out.p -= Z_ * lambda;
    out.dropped_rows = static_cast<int>(A_.rows() - conditioning_.spectrum.values.size());
  }
  out.summary.termination = out.p.allFinite() ? Termination::Converged : Termination::NumericalFailure;
  out.summary.iterations = 1;  // one direct solve
  if (out.dropped_rows)
    out.summary.message = std::to_string(out.dropped_rows) + " dependent constraint rows (minimum-norm multipliers, rank_tolerance " +
                          sci(policy_.rank_tolerance) + ")";
  assess(out, {H_, f, A_original_, ordered, scaling_, conditioning_}, policy_);
  return out;
}

std::string factorization_note(const QpSolver& solver) {
  if (const auto* kkt = dynamic_cast<const KktSolver*>(&solver)) return kkt->reused_factorization() ? "reused" : "factored";
  if (const auto* qr = dynamic_cast<const QrPenaltySolver*>(&solver)) return qr->reused_factorization() ? "reused" : "factored";
  const auto* rs = dynamic_cast<const RangeSpaceSolver*>(&solver);
  if (!rs || !rs->last_update()) return "factored";
  return "updated (+" + std::to_string(rs->last_update()->added) + " -" + std::to_string(rs->last_update()->removed) + " rows)";
}

}  // namespace fairshape::qp
