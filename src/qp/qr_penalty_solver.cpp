#include "fairshape/qp/qr_penalty_solver.h"
#include "fairshape/qp/same_matrix.h"

#include <Eigen/SPQRSupport>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseQR>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "fairshape/core/error.h"
#include "fairshape/core/message_format.h"
#include "fairshape/core/timer.h"
#include "fairshape/qp/constraint_policy.h"
#include "fairshape/problem/constrained_system.h"

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
  require_backend(backend);
  if (!(options.mu > 0) || !std::isfinite(options.mu)) throw InvalidConfig("qr_penalty: mu must be a positive number");
  if (options.refinement_steps < 0) throw InvalidConfig("qr_penalty: refinement_steps must be >= 0");
  if (!(options.max_mu >= options.mu)) throw InvalidConfig("qr_penalty: max_mu must be at least mu");
}
QrPenaltySolver::~QrPenaltySolver() = default;

namespace {
// max |after − before| / max |after|: how far one refinement step moved the answer.
double relative_change(const Eigen::MatrixXd& before, const Eigen::MatrixXd& after) {
  const double size = after.cwiseAbs().maxCoeff();
  const double moved = (after - before).cwiseAbs().maxCoeff();
  return size > 0 ? moved / size : moved;
}

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
  // R depends on H (through K), A and μ only: a step that keeps them keeps R. A solve that
  // raised μ left R at the raised one; a fresh analyze() starts from options_.mu, so that R
  // is not the one to keep.
  reused_ = options_.reuse_factorization && factorizations_ > 0 && mu_ == options_.mu && same_matrix(qp.hessian(), H_) &&
            same_matrix(qp.A, A_original_) && (qp.K.size() == 0 || same_matrix(qp.K, K_));
  if (reused_) {
    analyze_s_ = timer.seconds();
    return;
  }
  H_ = qp.hessian();
  A_original_ = qp.A;
  scaling_ = scale_rows(qp.A);  // unit rows: μ weighs every kind of row alike
  A_ = scaling_.scaled;
  At_ = A_.transpose();
  K_ = qp.K.size() ? qp.K : square_root_of(qp.hessian());
  factor(options_.mu);
  conditioning_ = constraint_conditioning(H_, A_, options_.policy.rank_tolerance);
  analyze_s_ = timer.seconds();
}

void QrPenaltySolver::factor(double mu) {
  ++factorizations_;
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
  // residual meets the tolerance and the answer has stopped moving; when a step halves neither
  // (the penalty's fixed point is too far for this μ, or the rows are inconsistent), μ grows
  // tenfold, up to max_mu. The residual alone is not enough: in the constraints' weak directions
  // (a condition estimate of 1e10) a residual of 1e-10 still leaves the answer 1e-4 off, and
  // each step's change is what is left of that error.
  int steps = 0;
  double change = std::numeric_limits<double>::infinity();
  // With no refinement steps (the paper's plain penalty) there is no change to measure: the
  // residual alone decides, as the option asks.
  const bool track_change = options_.refinement_steps > 0;
  const auto settled = [&](double c) { return !track_change || !(c > options_.solution_tolerance); };
  // The best answer over the μ tried: met rows first, then the smallest last change. A larger μ
  // resolves weak directions faster but squares into the semi-normal solve's rounding; once it
  // moves the answer more than a smaller μ did, the smaller μ's answer is kept.
  struct Round {
    Eigen::MatrixXd p;
    double residual, change, mu;
  };
  std::optional<Round> best;
  const auto better = [&](const Round& r) {
    const bool met = !(r.residual > tolerance), best_met = !(best->residual > tolerance);
    return met != best_met ? met : met ? r.change < best->change : r.residual < best->residual;
  };
  for (;;) {
    Eigen::MatrixXd shifted = b;
    double previous = std::numeric_limits<double>::infinity(), previous_change = previous;
    for (int step = 0; step <= options_.refinement_steps; ++step) {
      const Eigen::MatrixXd before = out.p;
      out.p = penalty_solve(f, shifted);
      const Eigen::MatrixXd Ap = A_ * out.p;
      const double now = relative_unit_residual(Ap, b);
      change = before.size() ? relative_change(before, out.p) : std::numeric_limits<double>::infinity();
      out.residual_history.push_back(now);
      ++steps;
      if (!(now > tolerance) && settled(change)) break;
      if (now > 0.5 * previous && change > 0.5 * previous_change) break;  // stalled at this μ
      previous = now;
      previous_change = change;
      shifted += b - Ap;
    }
    const Round round{out.p, out.residual_history.back(), change, mu_};
    const bool improved = !best || better(round);
    if (improved) best = round;
    const bool met = !(round.residual > tolerance) && settled(round.change);
    // Not met, whether the steps stalled or ran out (too slow at this μ): a larger μ, while it
    // helps. Without refinement steps μ stays as given (the plain penalty, as asked).
    if (met || !track_change || !improved || mu_ * 10 > options_.max_mu * (1 + 1e-12) || condition_ > 1e12) break;
    factor(mu_ * 10);
  }
  out.p = best->p;
  change = best->change;
  const double best_mu = best->mu;
  out.summary.termination = out.p.allFinite() ? Termination::Converged : Termination::NumericalFailure;
  out.summary.iterations = steps;  // penalty solves with the factorization(s)
  const auto note = [&](const std::string& text) { out.summary.message += (out.summary.message.empty() ? "" : "; ") + text; };
  if (best_mu != options_.mu) note("mu raised to " + sci(best_mu) + " (refinement stalled or too slow)");
  const std::string where = std::to_string(steps) + " penalty solves, the best at mu " + sci(best_mu) + " (refinement_steps " +
                            std::to_string(options_.refinement_steps) + ", max_mu " + sci(options_.max_mu) + ")";
  if (best->residual > tolerance) {
    note("qr_penalty stopped after " + where);
  } else if (!settled(change) && out.summary.termination == Termination::Converged) {
    // Every row met, but the answer still moves: it is uncertain by about that much.
    out.summary.termination = Termination::IllConditioned;
    note("the constraints are met but the answer still moved by " + sci(change) + " (relative) in its last step; " + where +
         ", above solution_tolerance " + sci(options_.solution_tolerance) +
         ": the rows have weak directions the penalty resolves slowly (a direct solver, kkt or range_space, does not)");
  }
  if (condition_ > 1e12) note("[mu A; K] is badly conditioned (estimate " + sci(condition_) + "): mu is too large for double precision");
  assess(out, {H_, f, A_original_, b_original, scaling_, conditioning_}, options_.policy);
  return out;
}

}  // namespace fairshape::qp
