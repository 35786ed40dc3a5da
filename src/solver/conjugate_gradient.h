// Jacobi-preconditioned conjugate gradients on the columns of x at once (each column its
// own scalars). The product with A is a parameter, so both back ends share the algorithm
// and differ only in the kernel (serial Eigen vs TBB row-parallel).
#pragma once

#include "fairshape/solver/iterative.h"

namespace fairshape {

template <class Multiply>
SolveSummary conjugate_gradient(const Multiply& A_times, const Eigen::VectorXd& diag, const Eigen::MatrixXd& b,
                                Eigen::MatrixXd& x, const IterativeOptions& opt, const IterationCallback& cb) {
  IterationMonitor monitor(
      opt, cb, [&](const Eigen::MatrixXd& v) { return 0.5 * v.cwiseProduct(A_times(v)).sum() - v.cwiseProduct(b).sum(); },
      /*krylov=*/true);
  CgErrorEstimate error(opt.error_delay);
  if (const auto problem = diagonal_problem(diag); !problem.empty()) {
    monitor.fail(problem);
    return monitor.summary();
  }
  const Eigen::VectorXd inv_diag = diag.cwiseInverse();
  const double b_norm = b.norm() > 0 ? b.norm() : 1.0;
  Eigen::MatrixXd r = b - A_times(x);
  Eigen::MatrixXd z = inv_diag.asDiagonal() * r;
  Eigen::MatrixXd p = z;
  Eigen::RowVectorXd rz = r.cwiseProduct(z).colwise().sum();
  if (!monitor.record(0, r.norm() / b_norm, x)) return monitor.summary();
  for (int it = 1;; ++it) {
    const Eigen::MatrixXd Ap = A_times(p);
    const Eigen::RowVectorXd pAp = p.cwiseProduct(Ap).colwise().sum();
    Eigen::RowVectorXd alpha(x.cols());
    for (Eigen::Index c = 0; c < x.cols(); ++c) alpha[c] = pAp[c] != 0 ? rz[c] / pAp[c] : 0.0;
    x += p * alpha.asDiagonal();
    r -= Ap * alpha.asDiagonal();
    if (monitor.should_check(it) && !monitor.record(it, r.norm() / b_norm, x)) {
      // The recursive residual drifts from b − Ax: the true one decides (a restart from it).
      const Eigen::MatrixXd true_r = b - A_times(x);
      if (!monitor.confirm_residual(it, true_r.norm() / b_norm)) break;
      r = true_r;
      z = inv_diag.asDiagonal() * r;
      p = z;
      rz = r.cwiseProduct(z).colwise().sum();
      continue;
    }
    if (monitor.estimates_error()) {
      error.push(alpha.dot(rz));
      if (error.ready() && !monitor.record_error(it, error.estimate(x.cwiseProduct(b - r).sum()))) break;
    }
    z = inv_diag.asDiagonal() * r;
    const Eigen::RowVectorXd rz_new = r.cwiseProduct(z).colwise().sum();
    for (Eigen::Index c = 0; c < x.cols(); ++c) p.col(c) = z.col(c) + (rz[c] != 0 ? rz_new[c] / rz[c] : 0.0) * p.col(c);
    rz = rz_new;
  }
  return monitor.summary();
}

}  // namespace fairshape
