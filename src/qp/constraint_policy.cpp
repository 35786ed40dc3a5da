#include "fairshape/qp/constraint_policy.h"

#include <Eigen/CholmodSupport>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>

#include "fairshape/core/config.h"
#include "fairshape/core/message_format.h"
#include "fairshape/problem/least_squares.h"

namespace fairshape::qp {

ConstraintPolicy read_constraint_policy(Config& cfg) {
  ConstraintPolicy p;
  p.rank_tolerance = cfg.get_number("rank_tolerance", p.rank_tolerance, 1e-16, 1e-2,
                                    "a direction of the unit-norm constraint rows weaker than this times the strongest counts "
                                    "as dependent (dropped; inconsistent targets then get a least-squares fit)");
  p.constraint_tolerance = cfg.get_number("constraint_tolerance", p.constraint_tolerance, 1e-15, 1,
                                          "largest unit-row residual, relative to the constrained values' size, still called "
                                          "converged (above: constraints_unmet)");
  p.max_condition = cfg.get_number("max_condition", p.max_condition, 1, 1e300,
                                   "largest condition estimate of the constraints' Schur complement still called converged "
                                   "(above: ill_conditioned)");
  return p;
}

double relative_unit_residual(const Eigen::MatrixXd& unit_Ap, const Eigen::MatrixXd& unit_b) {
  if (unit_b.size() == 0) return 0;
  const double size = std::max(unit_b.cwiseAbs().maxCoeff(), unit_Ap.cwiseAbs().maxCoeff());
  const double worst = (unit_Ap - unit_b).cwiseAbs().maxCoeff();
  return size > 0 ? worst / size : worst;
}

RowScaling scale_rows(const SparseMatrix& A) {
  RowScaling out;
  Eigen::VectorXd norm2 = Eigen::VectorXd::Zero(A.rows());
  for (int c = 0; c < A.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(A, c); it; ++it) norm2[it.row()] += it.value() * it.value();
  out.d.resize(A.rows());
  for (Eigen::Index i = 0; i < A.rows(); ++i) {
    if (norm2[i] > 0) {
      out.d[i] = 1 / std::sqrt(norm2[i]);
    } else {
      out.d[i] = 1;
      ++out.zero_rows;
    }
  }
  out.scaled = out.d.asDiagonal() * A;
  out.scaled.makeCompressed();
  return out;
}

int row_rank(const SparseMatrix& unit_rows, double rank_tolerance) {
  if (unit_rows.rows() == 0) return 0;
  const std::vector<int> reached = reached_columns(unit_rows);
  if (unit_rows.rows() > kConditionMaxRows || static_cast<double>(unit_rows.rows()) * static_cast<double>(reached.size()) > 2e7)
    return -1;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr;
  qr.setThreshold(rank_tolerance);
  qr.compute(Eigen::MatrixXd(unit_rows * row_picker(unit_rows.cols(), reached)));
  return static_cast<int>(qr.rank());
}

SchurSpectrum schur_spectrum(const Eigen::MatrixXd& S, int rank) {
  SchurSpectrum out;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(S);
  const Eigen::Index m = S.rows(), k = std::clamp<Eigen::Index>(rank, 0, m);
  if (eig.info() != Eigen::Success) {
    out.condition = std::numeric_limits<double>::infinity();
    return out;
  }
  // Eigen orders ascending: the k largest are the last k.
  out.vectors = eig.eigenvectors().rightCols(k).rowwise().reverse();
  out.values = eig.eigenvalues().tail(k).reverse();
  out.condition = k == 0 ? 1.0 : out.values[k - 1] > 0 ? out.values[0] / out.values[k - 1] : std::numeric_limits<double>::infinity();
  return out;
}

Eigen::MatrixXd SchurSpectrum::solve(const Eigen::MatrixXd& rhs) const {
  return vectors * (values.cwiseInverse().asDiagonal() * (vectors.transpose() * rhs));
}

double schur_rho(const SparseMatrix& H, const SparseMatrix& unit_rows) {
  const double h = H.rows() ? H.diagonal().cwiseAbs().maxCoeff() : 0.0;
  Eigen::VectorXd col2 = Eigen::VectorXd::Zero(unit_rows.cols());
  for (int c = 0; c < unit_rows.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(unit_rows, c); it; ++it) col2[c] += it.value() * it.value();
  const double a = col2.size() ? col2.maxCoeff() : 0.0;
  return h > 0 && a > 0 ? h / a : 1.0;
}

ConstraintConditioning constraint_conditioning(const SparseMatrix& H, const SparseMatrix& unit_rows, double rank_tolerance) {
  ConstraintConditioning out;
  out.rho = schur_rho(H, unit_rows);
  if (unit_rows.rows() == 0) {
    out.estimated = true;
    return out;
  }
  if (H.rows() > kConditionMaxUnknowns) return out;
  const int rank = row_rank(unit_rows, rank_tolerance);
  if (rank < 0) return out;
  SparseMatrix Hr = H + out.rho * SparseMatrix(unit_rows.transpose() * unit_rows);
  Hr.makeCompressed();
  Eigen::CholmodDecomposition<SparseMatrix> chol;
  chol.compute(Hr);
  if (chol.info() != Eigen::Success) return out;
  const Eigen::MatrixXd Z = chol.solve(Eigen::MatrixXd(SparseMatrix(unit_rows.transpose())));
  if (chol.info() != Eigen::Success || !Z.allFinite()) return out;
  out.spectrum = schur_spectrum(Eigen::MatrixXd(unit_rows * Z), rank);
  out.estimated = true;
  return out;
}

double ConstraintConditioning::weak_share(const SparseMatrix& H, const SparseMatrix& unit_rows, const Eigen::MatrixXd& f,
                                          const Eigen::MatrixXd& unit_b, const Eigen::MatrixXd& p, double max_condition) const {
  if (!estimated || spectrum.values.size() == 0) return 0;
  // Stationarity of ½pᵀH_ρp − gᵀp + λᵀ(Âp − b̂), g = f + ρÂᵀb̂:  Âᵀλ = f − Hp + ρÂᵀ(b̂ − Âp).
  const Eigen::MatrixXd w = f - H * p + rho * (SparseMatrix(unit_rows.transpose()) * (unit_b - unit_rows * p));
  const Eigen::MatrixXd AAt = Eigen::MatrixXd(unit_rows * SparseMatrix(unit_rows.transpose()));
  const Eigen::MatrixXd lambda = AAt.completeOrthogonalDecomposition().solve(Eigen::MatrixXd(unit_rows * w));
  const Eigen::MatrixXd c = spectrum.vectors.transpose() * lambda;  // per direction, per coordinate
  double weak = 0, total = 0;
  for (Eigen::Index i = 0; i < c.rows(); ++i) {
    const double e = spectrum.values[i] * c.row(i).squaredNorm();
    total += e;
    if (spectrum.values[i] * max_condition < spectrum.values[0]) weak += e;
  }
  return total > 0 ? weak / total : 0.0;
}

void assess(QpReport& out, const AssessedProgram& program, const ConstraintPolicy& policy) {
  out.condition_estimate = program.conditioning.condition();
  if (program.A.rows() == 0 || out.p.size() == 0) return;
  const Eigen::MatrixXd Ap = program.A * out.p;
  out.constraint_residual = (Ap - program.b).norm();
  if (out.summary.termination != Termination::Converged) return;
  const Eigen::VectorXd& d = program.rows.d;
  const Eigen::MatrixXd unit_b = d.asDiagonal() * program.b, unit_Ap = d.asDiagonal() * Ap;
  const double worst = (unit_Ap - unit_b).cwiseAbs().maxCoeff();
  const double relative = relative_unit_residual(unit_Ap, unit_b);
  const std::string notes = out.summary.message.empty() ? "" : "; " + out.summary.message;
  const std::string cond = program.conditioning.estimated ? sci(out.condition_estimate) : "not estimated";
  const double share = out.condition_estimate > policy.max_condition
                           ? program.conditioning.weak_share(program.H, program.rows.scaled, program.f, unit_b, out.p, policy.max_condition)
                           : 0.0;
  if (share > kMaxWeakShare) {
    out.summary.termination = Termination::IllConditioned;
    out.summary.message = "ill-posed constraints: " + sci(100 * share) + " % of the energy they impose sits in directions of their "
                          "Schur complement weaker than 1/max_condition (" + sci(policy.max_condition) + ") of the strongest; "
                          "condition estimate " + cond + " (nearly dependent constraints with different targets: e.g. two point "
                          "constraints very close together pulled apart, or eq. 7's curve rows); relative residual " +
                          sci(relative) + notes;
  } else if (!(relative <= policy.constraint_tolerance)) {
    out.summary.termination = Termination::ConstraintsUnmet;
    // Nearly dependent rows make a consistent set look inconsistent: the rank decision drops rows
    // whose targets the kept ones only nearly imply (40 points on a bilinear surface the sheet
    // represents exactly: condition 1e16). Say which it may be.
    const bool nearly_dependent = out.condition_estimate > policy.max_condition;
    out.summary.message = "constraints not met: relative residual " + sci(relative) + " (largest row " + sci(worst) +
                          ") above constraint_tolerance " + sci(policy.constraint_tolerance) +
                          (nearly_dependent ? " with nearly dependent rows (condition estimate " + cond + " above max_condition " +
                                                  sci(policy.max_condition) +
                                                  "): the targets may be consistent but not resolvable at this resolution "
                                                  "(points closer than the spans), or inconsistent"
                                            : " (inconsistent constraints, fitted in the least-squares sense, or a solver stopped "
                                              "short of them); condition estimate " + cond) +
                          notes;
  }
}

}  // namespace fairshape::qp
