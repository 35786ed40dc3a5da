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
#include "qp/constraint_policy.h"
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
  if (!(options.max_mu >= options.mu)) throw InvalidConfig("qr_penalty: max_mu must be at least mu");
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
  A_original_ = qp.A;
  scaling_ = scale_rows(qp.A);  // unit rows: μ weighs every kind of row alike
  A_ = scaling_.scaled;
  At_ = A_.transpose();
  K_ = qp.K.size() ? qp.K : square_root_of(qp.H);
  factor(options_.mu);
  conditioning_ = constraint_conditioning(H_, A_, options_.policy.rank_tolerance);
  analyze_s_ = timer.seconds();
}

void QrPenaltySolver::factor(double mu) {
  mu_ = mu;
  const double diag = H_.rows() ? H_.diagonal().cwiseAbs().maxCoeff() : 0.0;
  double a_max = 0;
  for (Eigen::Index i = 0; i < A_.nonZeros(); ++i) a_max = std::max(a_max, std::abs(A_.valuePtr()[i]));
  weight_ = mu * (diag > 0 && a_max > 0 ? std::sqrt(diag) / a_max : 1.0);
  const SparseMatrix weighted = weight_ * A_;
  SparseMatrix M = stack_rows({&weighted, &K_});
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

Eigen::MatrixXd QrPenaltySolver::penalty_solve(const Eigen::MatrixXd& f, const Eigen::MatrixXd& targets) const {
  // orthogonal: the energy's linear term through the corrected semi-normal equations (f need
  // not be Kᵀk), the constraint targets through Q (argmin ‖[μA; K] p − [μb; 0]‖).
  // semi_normal: everything through R alone.
  if (!options_.orthogonal) return semi_normal_solve(weight_ * weight_ * (At_ * targets) + f);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(rows_, f.cols());
  rhs.topRows(A_.rows()) = weight_ * targets;
  const Eigen::MatrixXd from_f = f.isZero(0) ? Eigen::MatrixXd::Zero(H_.rows(), f.cols()) : semi_normal_solve(f);
  return from_f + least_squares_(rhs);
}

QpReport QrPenaltySolver::solve(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b_original) {
  if (f.rows() != H_.rows() || b_original.rows() != A_.rows() || (b_original.rows() && b_original.cols() != f.cols()))
    throw InvalidInput("QR-penalty solve: right-hand sides do not match the analyzed program");
  if (mu_ != options_.mu) factor(options_.mu);  // a previous solve raised μ
  QpReport out;
  if (rank_ < H_.cols()) {
    out.p = Eigen::MatrixXd::Zero(H_.rows(), f.cols());
    out.summary.message = "[mu A; K] is numerically singular (rank " + std::to_string(rank_) + " of " + std::to_string(H_.cols()) +
                  "): the constraints do not pin the energy's null space, or mu is too large for the energy's scale";
    return out;
  }
  const Eigen::MatrixXd b = scaling_.d.asDiagonal() * b_original;
  const double tolerance = options_.policy.constraint_tolerance;
  // Van Loan's weighting method: the targets shifted by the accumulated residual, until the
  // residual meets the tolerance; when a step no longer halves it (the penalty's fixed point
  // is too far for this μ, or the rows are inconsistent), μ grows tenfold, up to max_mu.
  int steps = 0;
  for (;;) {
    Eigen::MatrixXd shifted = b;
    double previous = std::numeric_limits<double>::infinity();
    bool stalled = false;
    for (int step = 0; step <= options_.refinement_steps; ++step) {
      out.p = penalty_solve(f, shifted);
      const Eigen::MatrixXd Ap = A_ * out.p;
      const double now = relative_unit_residual(Ap, b);
      out.residual_history.push_back(now);
      ++steps;
      if (!(now > tolerance)) break;
      if (now > 0.5 * previous) {
        stalled = true;
        break;
      }
      previous = now;
      shifted += b - Ap;
    }
    const bool met = !(out.residual_history.back() > tolerance);
    if (met || !stalled || mu_ * 10 > options_.max_mu * (1 + 1e-12) || condition_ > 1e12) break;
    factor(mu_ * 10);
  }
  out.summary.termination = out.p.allFinite() ? Termination::Converged : Termination::NumericalFailure;
  out.summary.iterations = steps;  // penalty solves with the factorization(s)
  if (mu_ != options_.mu) out.summary.message = "mu raised to " + sci(mu_) + " (stalled refinement)";
  if (out.residual_history.back() > tolerance)
    out.summary.message += std::string(out.summary.message.empty() ? "" : "; ") + "qr_penalty stopped after " +
                           std::to_string(steps) + " penalty solves at mu " + sci(mu_) + " (refinement_steps " +
                           std::to_string(options_.refinement_steps) + ", max_mu " + sci(options_.max_mu) + ")";
  if (condition_ > 1e12)
    out.summary.message += std::string(out.summary.message.empty() ? "" : "; ") + "[mu A; K] is badly conditioned (estimate " +
                           sci(condition_) + "): mu is too large for double precision";
  assess(out, {H_, f, A_original_, b_original, scaling_, conditioning_}, options_.policy);
  return out;
}

}  // namespace fairshape::qp
