#include "qp/range_space_solver.h"

#include <Eigen/CholmodSupport>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/timer.h"
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

RangeSpaceSolver::RangeSpaceSolver() : chol_(std::make_unique<Cholmod>()) {}
RangeSpaceSolver::~RangeSpaceSolver() = default;

void RangeSpaceSolver::analyze(const QuadraticProgram& qp) {
  validate(qp);
  if (qp.A.rows() > kMaxRows)
    throw InvalidInput("range_space: " + std::to_string(qp.A.rows()) + " constraint rows are too many for its dense Schur complement (at most " +
                       std::to_string(kMaxRows) + "); use kkt or qr_penalty");
  const Timer timer;
  H_ = qp.H;
  A_ = qp.A;
  const double h_diag = H_.rows() ? H_.diagonal().cwiseAbs().maxCoeff() : 0.0;
  const SparseMatrix AtA = SparseMatrix(A_.transpose()) * A_;
  const double a_diag = AtA.rows() && AtA.nonZeros() ? AtA.diagonal().cwiseAbs().maxCoeff() : 0.0;
  rho_ = h_diag > 0 && a_diag > 0 ? h_diag / a_diag : 1.0;
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
  schur_.compute(S_);
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

void RangeSpaceSolver::add_rows(const SparseMatrix& rows) {
  if (rows.cols() != H_.cols())
    throw InvalidInput("range-space: new constraint rows have " + std::to_string(rows.cols()) + " columns, expected " +
                       std::to_string(H_.cols()));
  FAIRSHAPE_ASSERT(!singular_, "range-space: add_rows on a singular system");
  updown(true, rows);
  Triplets t;
  for (const SparseMatrix* part : {static_cast<const SparseMatrix*>(&A_), &rows})
    for (int col = 0; col < part->outerSize(); ++col)
      for (SparseMatrix::InnerIterator it(*part, col); it; ++it)
        t.emplace_back(static_cast<int>(it.row() + (part == &rows ? A_.rows() : 0)), col, it.value());
  SparseMatrix grown(A_.rows() + rows.rows(), A_.cols());
  grown.setFromTriplets(t.begin(), t.end());
  A_ = grown;
  rebuild_schur();
}

void RangeSpaceSolver::remove_rows(std::vector<int> rows) {
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  for (int r : rows)
    if (r < 0 || r >= A_.rows()) throw InvalidInput("range-space: no constraint row " + std::to_string(r));
  std::vector<int> keep;
  for (int r = 0, k = 0; r < A_.rows(); ++r) {
    if (k < static_cast<int>(rows.size()) && rows[k] == r) ++k;
    else keep.push_back(r);
  }
  updown(false, SparseMatrix(row_picker(A_.rows(), rows).transpose()) * A_);
  A_ = SparseMatrix(row_picker(A_.rows(), keep).transpose()) * A_;
  rebuild_schur();
}

QpReport RangeSpaceSolver::solve(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b) {
  if (f.rows() != H_.rows() || b.rows() != A_.rows() || (b.rows() && b.cols() != f.cols()))
    throw InvalidInput("range-space solve: right-hand sides do not match the analyzed program");
  QpReport out;
  if (singular_) {
    out.p = Eigen::MatrixXd::Zero(H_.rows(), f.cols());
    out.message = "H + rho AᵀA is not positive definite: the constraints do not pin the energy's null space";
    return out;
  }
  const Eigen::MatrixXd g = A_.rows() ? Eigen::MatrixXd(f + rho_ * (SparseMatrix(A_.transpose()) * b)) : f;
  const Eigen::MatrixXd y = solve_h(g);
  out.p = y;
  if (A_.rows()) {
    const Eigen::MatrixXd lambda = schur_.solve(Eigen::MatrixXd(A_ * y - b));
    out.p -= Z_ * lambda;
    out.dropped_rows = static_cast<int>(A_.rows() - schur_.rank());
  }
  out.constraint_residual = constraint_residual(A_, b, out.p);
  out.termination = out.p.allFinite() ? Termination::Converged : Termination::NumericalFailure;
  if (out.dropped_rows) out.message = std::to_string(out.dropped_rows) + " dependent constraint rows (minimum-norm multipliers)";
  return out;
}

}  // namespace fairshape::qp
