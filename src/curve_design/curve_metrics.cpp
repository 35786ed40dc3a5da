#include "fairshape/curve_design/curve_metrics.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>

#include "fairshape/curve_design/curve_constraint.h"
#include "fairshape/curve_design/curve_energy.h"

namespace fairshape {
namespace {

Vec3 plane_normal(const MatrixX3& X) {
  if ((X.col(2).array() == 0).all()) return Vec3::UnitZ();
  const Eigen::RowVector3d mean = X.colwise().mean();
  const MatrixX3 centered = X.rowwise() - mean;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(centered.transpose() * centered);
  return es.eigenvectors().col(0);  // smallest eigenvalue first
}

}  // namespace

int count_wrinkles(const MatrixX3& X, bool closed) {
  const int n = static_cast<int>(X.rows());
  const Vec3 normal = plane_normal(X);
  int changes = 0, sign = 0;
  const int first = closed ? 0 : 1, last = closed ? n : n - 1;
  for (int i = first; i < last; ++i) {
    const Vec3 a = (X.row(i) - X.row((i + n - 1) % n)).transpose(), b = (X.row((i + 1) % n) - X.row(i)).transpose();
    const double turn = std::atan2(a.cross(b).dot(normal), a.dot(b));
    if (std::abs(turn) < 1e-4) continue;
    const int s = turn > 0 ? 1 : -1;
    if (sign != 0 && s != sign) ++changes;
    sign = s;
  }
  return changes;
}

CurveMetrics measure_curve(const MatrixX3& X, bool closed, const Eigen::VectorXd& ref, const MatrixX3& attractor) {
  CurveMetrics m;
  const Eigen::VectorXd l = segment_lengths(X, closed);
  const Eigen::ArrayXd rel = (l - ref).cwiseAbs().cwiseQuotient(ref).array();
  m.length_error_max = rel.maxCoeff();
  m.length_error_rms = std::sqrt(rel.square().mean());
  m.total_length_change = (l.sum() - ref.sum()) / ref.sum();
  m.bending_energy = stencil_energy(bending_stencils(static_cast<int>(X.rows()), closed), X, attractor);
  m.distance_to_attractor = (X - attractor).squaredNorm();
  m.wrinkles = count_wrinkles(X, closed);
  return m;
}

double handle_reach(const MatrixX3& R, const MatrixX3& D, const MatrixX3& X, const std::vector<int>& moved) {
  double reach = 1;
  for (int p : moved) {
    const Eigen::RowVector3d asked = D.row(p) - R.row(p);
    const double a2 = asked.squaredNorm();
    if (!(a2 > 0)) continue;
    reach = std::min(reach, (X.row(p) - R.row(p)).dot(asked) / a2);
  }
  return reach;
}

double worst_overstretch(const MatrixX3& X, const Eigen::VectorXd& lengths, bool closed, int stride, const std::vector<int>& moved) {
  const int n = static_cast<int>(X.rows());
  std::vector<double> arc(static_cast<std::size_t>(n) + 1, 0.0);  // arc[i]: length from point 0 to point i
  for (int i = 0; i < static_cast<int>(lengths.size()); ++i) arc[static_cast<std::size_t>(i) + 1] = arc[static_cast<std::size_t>(i)] + lengths[i];
  const double total = closed ? arc[static_cast<std::size_t>(n)] : 0;
  double worst = -1;
  for (int p : moved)
    for (int q = 0; q < n; q += stride) {
      if (q == p) continue;
      double between = std::abs(arc[static_cast<std::size_t>(p)] - arc[static_cast<std::size_t>(q)]);
      if (closed) between = std::min(between, total - between);
      if (between > 0) worst = std::max(worst, (X.row(p) - X.row(q)).norm() / between - 1);
    }
  return worst;
}

}  // namespace fairshape
