#include "fairshape/problem/anderson_acceleration.h"

#include <Eigen/QR>

namespace fairshape {

Eigen::VectorXd AndersonAcceleration::next(const Eigen::VectorXd& x, const Eigen::VectorXd& g) {
  const Eigen::VectorXd f = g - x;
  if (f_prev_.size() == f.size()) {
    dF_.push_back(f - f_prev_);
    dG_.push_back(g - g_prev_);
    while (static_cast<int>(dF_.size()) > history_) dF_.pop_front(), dG_.pop_front();
  }
  f_prev_ = f;
  g_prev_ = g;
  if (dF_.empty()) return g;
  const auto m = static_cast<Eigen::Index>(dF_.size());
  Eigen::MatrixXd F(f.size(), m), G(f.size(), m);
  for (Eigen::Index k = 0; k < m; ++k) F.col(k) = dF_[static_cast<std::size_t>(k)], G.col(k) = dG_[static_cast<std::size_t>(k)];
  const Eigen::VectorXd gamma = F.colPivHouseholderQr().solve(f);
  if (!gamma.allFinite()) return g;  // a degenerate history: the plain step
  return g - G * gamma;
}

}  // namespace fairshape
