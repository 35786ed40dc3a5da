#include "fairshape/curve_design/curve_plane.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "fairshape/core/error.h"

namespace fairshape {

CurvePlane fit_plane(const std::vector<const MatrixX3*>& curves) {
  CurvePlane plane;
  Eigen::Index count = 0;
  Vec3 sum = Vec3::Zero(), lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const MatrixX3* X : curves) {
    count += X->rows();
    for (Eigen::Index i = 0; i < X->rows(); ++i) {
      const Vec3 x = X->row(i).transpose();
      sum += x;
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
  }
  if (count == 0) return plane;
  plane.origin = sum / static_cast<double>(count);
  plane.size = (hi - lo).norm();
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const MatrixX3* X : curves)
    for (Eigen::Index i = 0; i < X->rows(); ++i) {
      const Vec3 d = X->row(i).transpose() - plane.origin;
      cov += d * d.transpose();
    }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Eigen::Vector3d ev = eig.eigenvalues().cwiseMax(0.0);
  // Collinear (the middle eigenvalue is rounding of the largest): any plane through the line.
  if (ev[1] <= 1e-24 * ev[2]) {
    const Vec3 u = eig.eigenvectors().col(2);
    Vec3 n = Vec3::UnitZ() - u.z() * u;
    if (n.norm() < 1e-6) n = Vec3::UnitX() - u.x() * u;
    plane.normal = n.normalized();
  } else {
    plane.normal = eig.eigenvectors().col(0).normalized();
  }
  for (const MatrixX3* X : curves) plane.deviation = std::max(plane.deviation, distance_from_plane(*X, plane));
  plane.planar = plane.deviation <= kPlanarTolerance * plane.size;
  return plane;
}

double distance_from_plane(const MatrixX3& X, const CurvePlane& plane) {
  double worst = 0;
  for (Eigen::Index i = 0; i < X.rows(); ++i)
    worst = std::max(worst, std::abs(plane.normal.dot(X.row(i).transpose() - plane.origin)));
  return worst;
}

InPlane::InPlane(std::vector<int> points, const CurvePlane& plane)
    : points_(std::move(points)), plane_(plane), scale_(plane.size > 0 ? plane.size : 1.0) {}

ConstraintRow InPlane::touched(int row) const {
  ConstraintRow r;
  r.row = row;
  r.size = 1;
  r.points = {points_[static_cast<std::size_t>(row)], points_[static_cast<std::size_t>(row)]};
  return r;
}

void InPlane::evaluate_at(ConstraintRow& r, const Vec3* x) const {
  r.value = plane_.normal.dot(x[0] - plane_.origin);
  r.gradient[0] = plane_.normal;
}

double InPlane::relative_error(const MatrixX3& X, double curve_length) const {
  double worst = 0;
  for (int p : points_) worst = std::max(worst, std::abs(plane_.normal.dot(X.row(p).transpose() - plane_.origin)));
  return worst / curve_length;
}

std::vector<int> in_plane_points(int n, const std::vector<const CurveConstraint*>& constraints) {
  std::vector<int> group(static_cast<std::size_t>(n));
  std::iota(group.begin(), group.end(), 0);
  const auto find = [&](int i) {
    while (group[static_cast<std::size_t>(i)] != i) i = group[static_cast<std::size_t>(i)] = group[static_cast<std::size_t>(group[static_cast<std::size_t>(i)])];
    return i;
  };
  std::vector<char> held(static_cast<std::size_t>(n), 0);  // the group's normal component is held already
  for (const CurveConstraint* c : constraints) {
    if (const auto* t = dynamic_cast<const FixedTangents*>(c))
      for (const auto& [a, b] : t->chords()) group[static_cast<std::size_t>(find(a))] = find(b);
  }
  for (const CurveConstraint* c : constraints)
    if (const auto* p = dynamic_cast<const PinnedPoints*>(c))
      for (int q : p->points()) held[static_cast<std::size_t>(find(q))] = 1;
  std::vector<int> out;
  for (int i = 0; i < n; ++i) {
    const int g = find(i);
    if (held[static_cast<std::size_t>(g)]) continue;
    held[static_cast<std::size_t>(g)] = 1;  // one row per group: its first point
    out.push_back(i);
  }
  return out;
}

bool constraints_in_plane(const std::vector<const CurveConstraint*>& constraints, const CurvePlane& plane) {
  const double tol = kPlanarTolerance * plane.size;
  for (const CurveConstraint* c : constraints) {
    if (const auto* p = dynamic_cast<const PinnedPoints*>(c))
      if (distance_from_plane(p->targets(), plane) > tol) return false;
    if (const auto* t = dynamic_cast<const FixedTangents*>(c))
      for (Eigen::Index k = 0; k < t->directions().rows(); ++k)
        if (std::abs(plane.normal.dot(t->directions().row(k).transpose())) > kPlanarTolerance) return false;
  }
  return true;
}

}  // namespace fairshape
