#include "qp/qr_penalty_solver.h"

#include <Eigen/SPQRSupport>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseQR>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/message_format.h"
#include "core/timer.h"
#include "problem/constrained_system.h"

namespace fairshape::qp {

SparseMatrix square_root_of(const SparseMatrix& H) {
  const double diag = H.rows() ? H.diagonal().cwiseAbs().maxCoeff() : 0.0;
  SparseMatrix shifted = H;
  for (Eigen::Index i = 0; i < H.rows(); ++i) shifted.coeffRef(i, i) += 1e-12 * (diag > 0 ? diag : 1.0);
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(shifted);
  if (ldlt.info() != Eigen::Success) throw SolverError("QR-penalty: H is not positive semi-definite (LDLᵀ failed)");
  const Eigen::VectorXd d = ldlt.vectorD().cwiseMax(0).cwiseSqrt();
  const SparseMatrix Lt = SparseMatrix(ldlt.matrixL()).transpose();
  // K P⁻¹... with P H Pᵀ = L D Lᵀ: H = (D^½ Lᵀ P)ᵀ (D^½ Lᵀ P).
  const SparseMatrix K = d.asDiagonal() * Lt;
  return K * ldlt.permutationP();
}

QrPenaltySolver::QrPenaltySolver(Backend backend, QrPenaltyOptions options) : backend_(backend), options_(options) {
  if (!(options.mu > 0) || !std::isfinite(options.mu)) throw InvalidConfig("qr_penalty: mu must be a positive number");
  if (options.refinement_steps < 0) throw InvalidConfig("qr_penalty: refinement_steps must be >= 0");
}
QrPenaltySolver::~QrPenaltySolver() = default;

namespace {
template <class QR>
void factor_r(QR& qr, const SparseMatrix& M, SparseMatrix& R, Eigen::VectorXi& permutation, int& rank) {
  qr.compute(M);
  if (qr.info() != Eigen::Success) throw SolverError("QR-penalty: sparse QR of [mu A; K] failed");
  rank = static_cast<int>(qr.rank());
  const auto perm = qr.colsPermutation();  // SPQR returns it by value: keep it alive
  permutation = perm.indices().template cast<int>();  // SPQR indexes with long
  const SparseMatrix full = qr.matrixR();
  R = full.topRows(std::min<Eigen::Index>(full.rows(), M.cols()));  // n × n when M has full column rank
}
}  // namespace

void QrPenaltySolver::analyze(const QuadraticProgram& qp) {
  validate(qp);
  const Timer timer;
  H_ = qp.H;
  A_ = qp.A;
  At_ = A_.transpose();
  const SparseMatrix K = qp.K.size() ? qp.K : square_root_of(qp.H);
  const double diag = H_.rows() ? H_.diagonal().cwiseAbs().maxCoeff() : 0.0;
  double a_max = 0;
  for (Eigen::Index i = 0; i < A_.nonZeros(); ++i) a_max = std::max(a_max, std::abs(A_.valuePtr()[i]));
  weight_ = options_.mu * (diag > 0 && a_max > 0 ? std::sqrt(diag) / a_max : 1.0);
  const SparseMatrix weighted = weight_ * A_;
  SparseMatrix M = stack_rows({&weighted, &K});
  M.makeCompressed();
  rows_ = M.rows();
  if (backend_ == Backend::Reference) {
    auto qr = std::make_shared<Eigen::SparseQR<SparseMatrix, Eigen::COLAMDOrdering<int>>>();
    factor_r(*qr, M, R_, permutation_, rank_);
    if (options_.orthogonal) least_squares_ = [qr](const Eigen::MatrixXd& rhs) { return Eigen::MatrixXd(qr->solve(rhs)); };
  } else {
    auto qr = std::make_shared<Eigen::SPQR<SparseMatrix>>();
    factor_r(*qr, M, R_, permutation_, rank_);
    if (options_.orthogonal) least_squares_ = [qr](const Eigen::MatrixXd& rhs) { return Eigen::MatrixXd(qr->solve(rhs)); };
  }
  Rt_ = R_.transpose();
  if (R_.rows() < R_.cols()) rank_ = std::min(rank_, static_cast<int>(R_.rows()));
  const Eigen::VectorXd d = R_.diagonal().cwiseAbs();
  condition_ = d.size() && d.minCoeff() > 0 ? d.maxCoeff() / d.minCoeff() : std::numeric_limits<double>::infinity();
  analyze_s_ = timer.seconds();
}

Eigen::MatrixXd QrPenaltySolver::normal_product(const Eigen::MatrixXd& p) const {
  return H_ * p + weight_ * weight_ * (At_ * (A_ * p));
}

Eigen::MatrixXd QrPenaltySolver::semi_normal_solve(const Eigen::MatrixXd& rhs) const {
  // MᵀM = P RᵀR Pᵀ: permute, two triangular solves, permute back.
  const auto once = [&](const Eigen::MatrixXd& y) {
    Eigen::MatrixXd permuted(y.rows(), y.cols());
    for (Eigen::Index c = 0; c < permutation_.size(); ++c) permuted.row(c) = y.row(permutation_[c]);
    const Eigen::MatrixXd z = Rt_.triangularView<Eigen::Lower>().solve(permuted);
    const Eigen::MatrixXd w = R_.triangularView<Eigen::Upper>().solve(z);
    Eigen::MatrixXd x(y.rows(), y.cols());
    for (Eigen::Index c = 0; c < permutation_.size(); ++c) x.row(permutation_[c]) = w.row(c);
    return x;
  };
  Eigen::MatrixXd x = once(rhs);
  x += once(rhs - normal_product(x));  // the correction step
  return x;
}

QpReport QrPenaltySolver::solve(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b) {
  if (f.rows() != H_.rows() || b.rows() != A_.rows() || (b.rows() && b.cols() != f.cols()))
    throw InvalidInput("QR-penalty solve: right-hand sides do not match the analyzed program");
  QpReport out;
  out.condition_estimate = condition_;
  if (rank_ < H_.cols()) {
    out.p = Eigen::MatrixXd::Zero(H_.rows(), f.cols());
    out.summary.message = "[mu A; K] is numerically singular (rank " + std::to_string(rank_) + " of " + std::to_string(H_.cols()) +
                  "): the constraints do not pin the energy's null space, or mu is too large for the energy's scale";
    return out;
  }
  // orthogonal: the energy's linear term through the corrected semi-normal equations (f need
  // not be Kᵀk), the constraint targets through Q (argmin ‖[μA; K] p − [μb; 0]‖).
  // semi_normal: everything through R alone.
  Eigen::MatrixXd from_f;
  if (options_.orthogonal) from_f = f.isZero(0) ? Eigen::MatrixXd::Zero(H_.rows(), f.cols()) : semi_normal_solve(f);
  Eigen::MatrixXd shifted = b;  // Van Loan's weighting method: b plus the accumulated residual
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(rows_, f.cols());
  for (int step = 0; step <= options_.refinement_steps; ++step) {
    if (options_.orthogonal) {
      rhs.topRows(A_.rows()) = weight_ * shifted;
      out.p = from_f + least_squares_(rhs);
    } else {
      out.p = semi_normal_solve(weight_ * weight_ * (At_ * shifted) + f);
    }
    const Eigen::MatrixXd residual = b - A_ * out.p;
    out.residual_history.push_back(residual.norm());
    shifted += residual;
  }
  out.constraint_residual = out.residual_history.back();
  out.summary.termination = out.p.allFinite() ? Termination::Converged : Termination::NumericalFailure;
  out.summary.iterations = 1;  // one direct solve
  if (condition_ > 1e12)
    out.summary.message = "warning: [mu A; K] is badly conditioned (estimate " + sci(condition_) +
                  "): mu is too large for double precision";
  return out;
}

}  // namespace fairshape::qp
