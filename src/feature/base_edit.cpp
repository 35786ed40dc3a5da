#include "fairshape/feature/base_edit.h"

#include <cmath>

namespace fairshape::feature {

MatrixX3 bumped_positions(const SurfaceMesh& base, const BaseEdit& e, double diag) {
  Eigen::Index centre = 0;
  (base.positions().rowwise() - e.nearest.transpose()).rowwise().squaredNorm().minCoeff(&centre);
  const Vec3 c = base.position(static_cast<int>(centre));
  MatrixX3 X = base.positions();
  const double R = e.radius * diag;
  for (int v = 0; v < base.n_vertices(); ++v) {
    const double t = (base.position(v) - c).norm() / R;
    if (t < 1) X.row(v) += std::pow(1 - t * t, 3) * e.offset.transpose();
  }
  return X;
}

}  // namespace fairshape::feature
