// Anderson acceleration of a fixed-point iteration x ← G(x) (Walker & Ni, "Anderson acceleration
// for fixed-point iterations"; Peng et al., "Anderson acceleration for geometry optimization and
// physics simulation"): the next iterate combines the last few G values with the weights that
// best cancel their residuals f = G(x) − x in least squares. The weights sum to one, so the
// next iterate is an affine combination of G values: it keeps any linear equations every G
// value meets (a constrained solve's constraints).
#pragma once

#include <deque>

#include <Eigen/Dense>

namespace fairshape {

class AndersonAcceleration {
 public:
  explicit AndersonAcceleration(int history) : history_(history) {}
  //! The iterate after x, given g = G(x) (same size every call).
  Eigen::VectorXd next(const Eigen::VectorXd& x, const Eigen::VectorXd& g);
  //! Forgets the history (after a safeguard rejected an accelerated iterate).
  void reset() { dF_.clear(), dG_.clear(), f_prev_.resize(0), g_prev_.resize(0); }

 private:
  int history_;
  std::deque<Eigen::VectorXd> dF_, dG_;  // differences of consecutive residuals and G values
  Eigen::VectorXd f_prev_, g_prev_;
};

}  // namespace fairshape
