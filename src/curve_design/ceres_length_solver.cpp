#include "fairshape/curve_design/ceres_length_solver.h"

#include "fairshape/curve_design/length_manifold.h"
#include "fairshape/curve_design/second_order.h"

#include <ceres/ceres.h>

#include <cmath>

#include "fairshape/core/config.h"
#include "fairshape/core/timer.h"
#include "fairshape/curve_design/curve_plane.h"

namespace fairshape {
namespace {

// sqrt(2w)·(Σ_j c_j X_j − o): Ceres minimizes ½Σ|r|², so ½|r|² = w·|stencil|².
class StencilCost final : public ceres::CostFunction {
 public:
  StencilCost(const CurveStencil& s, const Eigen::RowVector3d& offset, double weight)
      : s_(s), offset_(offset.transpose()), scale_(std::sqrt(2 * weight)) {
    set_num_residuals(3);
    for (int j = 0; j < s.size; ++j) mutable_parameter_block_sizes()->push_back(3);
  }
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override {
    Eigen::Map<Vec3> r(residuals);
    r = -offset_;
    for (int j = 0; j < s_.size; ++j) r += s_.coeffs[j] * Eigen::Map<const Vec3>(x[j]);
    r *= scale_;
    if (jacobians)
      for (int j = 0; j < s_.size; ++j)
        if (jacobians[j]) {  // 3×3 row-major: scale·c_j·I
          Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> block(jacobians[j]);
          block = scale_ * s_.coeffs[j] * Eigen::Matrix3d::Identity();
        }
    return true;
  }

 private:
  CurveStencil s_;
  Vec3 offset_;
  double scale_;
};

// sqrt(μ)·(g + λ/μ), g = f/scale: ½ of its square is λg + (μ/2)g² + const.
class AugmentedRowCost final : public ceres::CostFunction {
 public:
  AugmentedRowCost(const CurveConstraint& c, ConstraintRow row, double scale, const double* lambda, const double* mu)
      : c_(c), row_(row), inv_scale_(1 / scale), lambda_(lambda), mu_(mu) {
    set_num_residuals(1);
    for (int k = 0; k < row.size; ++k) mutable_parameter_block_sizes()->push_back(3);
  }
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override {
    ConstraintRow r = row_;
    const Vec3 pts[2] = {Eigen::Map<const Vec3>(x[0]), Eigen::Map<const Vec3>(x[r.size - 1])};
    c_.evaluate_at(r, pts);
    const double root_mu = std::sqrt(*mu_);
    residuals[0] = root_mu * (r.value * inv_scale_ + *lambda_ / *mu_);
    if (jacobians)
      for (int k = 0; k < r.size; ++k)
        if (jacobians[k]) {
          Eigen::Map<Vec3> row(jacobians[k]);
          row = root_mu * inv_scale_ * r.gradient[k];
        }
    return true;
  }

 private:
  const CurveConstraint& c_;
  ConstraintRow row_;
  double inv_scale_;
  const double* lambda_;
  const double* mu_;
};

}  // namespace

LengthSolveReport CeresLengthSolver::solve(const LengthProblem& p, const MatrixX3& start) const {
  const Timer timer;
  LengthSolveReport rep;
  if (p.has_dense_rows()) {
    // One residual over every point would make Ceres's normal equations dense (O(n³) per step):
    // refused, not approximated.
    rep.points = start;
    rep.summary.termination = Termination::InvalidInput;
    rep.summary.message = "solver ceres does not take the total_length constraint (a residual over every point makes "
                          "its normal equations dense); the solvers that do: linearized, trust_region";
    return rep;
  }
  MatrixX3 X = start;  // row-major: point i's block is X.data() + 3i
  const int m = p.n_constraint_rows();
  std::vector<double> lambda(m, 0.0);
  // μ in units of the objective's curvature: a segment constraint g = f/l² has gradient
  // ~2/l, so μ·4/l² against the largest diagonal entry of Q balances the two.
  const double mean_l = p.reference_lengths().mean();
  double mu = o_.initial_penalty * p.objective_hessian().diagonal().maxCoeff() * mean_l * mean_l / 4;

  ceres::Problem::Options po;
  ceres::Problem problem(po);
  for (int i = 0; i < p.n_points(); ++i) problem.AddParameterBlock(X.data() + 3 * i, 3);
  for (const auto& e : p.energies()) {
    if (e.weight <= 0) continue;
    for (const auto& s : e.stencils) {
      const Eigen::RowVector3d offset =
          (s.attractor_point >= 0 ? Eigen::RowVector3d(p.attractor().row(s.attractor_point)) : Eigen::RowVector3d::Zero()) +
          s.constant.transpose();
      std::vector<double*> blocks;
      for (int j = 0; j < s.size; ++j) blocks.push_back(X.data() + 3 * s.points[j]);
      problem.AddResidualBlock(new StencilCost(s, offset, e.weight), nullptr, blocks);
    }
  }
  int global = 0;
  for (const auto& c : p.constraints())
    for (int r = 0; r < c->rows(); ++r, ++global) {
      const ConstraintRow row = c->touched(r);
      std::vector<double*> blocks;
      for (int k = 0; k < row.size; ++k) blocks.push_back(X.data() + 3 * row.points[k]);
      problem.AddResidualBlock(new AugmentedRowCost(*c, row, c->row_scale(r), &lambda[global], &mu), nullptr, blocks);
    }

  ceres::Solver::Options so;
  so.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  so.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  so.logging_type = ceres::SILENT;
  so.minimizer_progress_to_stdout = false;
  so.num_threads = o_.threads;
  // Each round only has to be accurate enough for the next multiplier update.
  so.function_tolerance = 1e-14;
  so.gradient_tolerance = 1e-14;
  so.parameter_tolerance = 1e-14;
  so.max_num_iterations = 50;

  // The tolerance asked, or this curve's rounding floor when larger (length_manifold.h).
  const double tol = attainable_length_tolerance(p, start, o_.tolerances.length);
  double previous_violation = INFINITY;
  for (int round = 0; round < o_.max_rounds && rep.solves < o_.tolerances.max_solves; ++round) {
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
    rep.solves += summary.num_successful_steps + summary.num_unsuccessful_steps;
    rep.summary.iterations = rep.solves;
    rep.outer_iterations = round + 1;
    if (summary.termination_type == ceres::FAILURE || !X.allFinite()) {
      rep.points = X;
      rep.summary.message = "Ceres failed in round " + std::to_string(round + 1) + ": " + summary.message;
      return rep;
    }
    // A planar problem's in-plane rows (curve_plane.h) are linear in one point: the penalty
    // meets them only to its tolerance, the orthogonal projection exactly, moving each point by
    // that residual (lengths change by its square); everything below is measured after it.
    for (const auto& c : p.constraints())
      if (const auto* plane = dynamic_cast<const InPlane*>(c.get()))
        for (int q : plane->points()) {
          const Vec3& nrm = plane->plane().normal;
          X.row(q) -= nrm.dot(X.row(q).transpose() - plane->plane().origin) * nrm.transpose();
        }
    const std::vector<ConstraintRow> rows = p.rows(X);
    double violation = 0;
    for (int r = 0; r < m; ++r) violation = std::max(violation, std::abs(rows[r].value / p.row_scale(r)));
    rep.length_error = p.max_relative_length_error(X);
    rep.summary.residual = rep.length_error;
    rep.pin_error = p.max_relative_pin_error(X);
    const double stat = o_.tolerances.stationarity > 0 ? p.stationarity(X) : 0.0;
    rep.history.push_back({rep.solves, rep.length_error, stat, timer.seconds(), p.objective(X)});
    if (rep.length_error <= tol && rep.pin_error <= tol && stat <= o_.tolerances.stationarity) {
      rep.points = X;
      rep.summary.termination = Termination::Converged;
      rep.summary.message = "converged after " + std::to_string(round + 1) + " augmented-Lagrangian round(s)";
      judge_second_order(p, rep, o_.tolerances.stationarity > 0, o_.tolerances.second_order);  // a saddle is reported, not converged (no escape here)
      return rep;
    }
    for (int r = 0; r < m; ++r) lambda[r] += mu * rows[r].value / p.row_scale(r);
    if (violation > 0.25 * previous_violation) mu *= 10;
    previous_violation = violation;
  }
  rep.points = X;
  rep.summary.termination = Termination::MaxIterations;
  rep.summary.message = "not converged after " + std::to_string(rep.outer_iterations) + " augmented-Lagrangian rounds (" +
                std::to_string(rep.solves) + " Gauss-Newton steps): max relative length error " +
                format_default(rep.length_error);
  return rep;
}

}  // namespace fairshape
