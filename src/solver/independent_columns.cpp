#include "fairshape/solver/independent_columns.h"

#include <cmath>
#include <string>

#include <Eigen/QR>

#include "fairshape/problem/constrained_system.h"

namespace fairshape {

std::optional<ColumnDependence> dependent_columns(const Eigen::MatrixXd& B, double tolerance) {
  const double norm = B.norm();
  if (B.cols() < 2 || norm == 0 || !std::isfinite(norm)) return std::nullopt;
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(B);
  const Eigen::Index rank = [&] {
    const auto& R = qr.matrixR();
    Eigen::Index r = 0;
    while (r < B.cols() && std::abs(R(r, r)) > tolerance * norm) ++r;
    return r;
  }();
  if (rank == B.cols()) return std::nullopt;
  ColumnDependence d;
  const auto& perm = qr.colsPermutation().indices();
  for (Eigen::Index k = 0; k < rank; ++k) d.independent.push_back(perm(k));
  Eigen::MatrixXd Br(B.rows(), rank);
  for (Eigen::Index k = 0; k < rank; ++k) Br.col(k) = B.col(d.independent[k]);
  // The combination of every column from the independent ones (least squares), then checked:
  // a column that the kept ones reproduce only approximately keeps the block solve.
  d.combination = rank == 0 ? Eigen::MatrixXd::Zero(0, B.cols()) : Eigen::MatrixXd(Br.colPivHouseholderQr().solve(B));
  const double misfit = rank == 0 ? norm : (Br * d.combination - B).norm();
  if (misfit > tolerance * norm) return std::nullopt;
  return d;
}

SolveSummary solve_independent_columns(Solver& solver, const SparseMatrix& A, const Eigen::MatrixXd& B,
                                       Eigen::MatrixXd& X, const IterationCallback& cb) {
  const std::optional<ColumnDependence> d = dependent_columns(B);
  // The start must have B's dependence too, or combining the columns' solutions would change it.
  const auto pick = [&](const Eigen::MatrixXd& M) {
    Eigen::MatrixXd out(M.rows(), static_cast<Eigen::Index>(d->independent.size()));
    for (std::size_t k = 0; k < d->independent.size(); ++k) out.col(static_cast<Eigen::Index>(k)) = M.col(d->independent[k]);
    return out;
  };
  if (!d || d->independent.empty() || X.cols() != B.cols() ||
      (X.norm() > 0 && (pick(X) * d->combination - X).norm() > 1e-13 * X.norm()))
    return solver.solve(A, B, X, cb);
  const Eigen::MatrixXd Br = pick(B);
  Eigen::MatrixXd Xr = pick(X), full;
  IterationCallback expanded;
  if (cb)
    expanded = [&](const IterationRecord& r) {
      full = *r.x * d->combination;
      // The solver's energy is of its own columns; the caller's is of every column.
      const double energy = std::isnan(r.energy) ? r.energy
                                                 : 0.5 * (full.transpose() * (A * full)).trace() - B.cwiseProduct(full).sum();
      return cb({r.iteration, r.residual, r.seconds, energy, &full});
    };
  SolveSummary s = solver.solve(A, Br, Xr, expanded);
  X = Xr * d->combination;
  if (s.residual >= 0) s.residual = relative_residual(A, B, X);  // of every column, as the caller asked
  const std::string note = "solved " + std::to_string(Br.cols()) + " independent of " + std::to_string(B.cols()) +
                           " right-hand-side columns";
  s.message = s.message.empty() ? note : s.message + "; " + note;
  return s;
}

}  // namespace fairshape
