#include "qp/range_space_solver.h"
#include "qp/constraint_policy.h"
#include "qp/row_dependence.h"

#include <Eigen/CholmodSupport>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/message_format.h"
#include "core/timer.h"
#include "problem/constrained_system.h"
#include "problem/least_squares.h"

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

void RangeSpaceSolver::analyze(const QuadraticProgram& qp) {
  validate(qp);
  if (qp.A.rows() > kMaxRows)
    throw InvalidInput("range_space: " + std::to_string(qp.A.rows()) + " constraint rows are too many for its dense Schur complement (at most " +
                       std::to_string(kMaxRows) + "); use kkt or qr_penalty");
  const Timer timer;
  H_ = qp.H;
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
  const Eigen::MatrixXd b = scaling_.d.asDiagonal() * b_original;
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
  assess(out, {H_, f, A_original_, b_original, scaling_, conditioning_}, policy_);
  return out;
}

}  // namespace fairshape::qp
