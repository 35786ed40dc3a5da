#include "fairshape/curve_design/detail_frames.h"

#include <Eigen/Geometry>
#include <cmath>

namespace fairshape {
namespace {

int segment_count(const MatrixX3& p, bool closed) { return static_cast<int>(closed ? p.rows() : p.rows() - 1); }

Vec3 direction(const MatrixX3& p, int i) {
  const Vec3 d = (p.row((i + 1) % p.rows()) - p.row(i)).transpose();
  const double s = d.norm();
  return s > 0 ? Vec3(d / s) : Vec3::UnitX();
}

// The least rotation taking unit u to unit v; a half turn about an axis normal to u (the z
// axis when it is one, so plane curves stay in their plane) when they are opposite.
Eigen::Matrix3d least_rotation(const Vec3& u, const Vec3& v) {
  if (u.dot(v) < -1 + 1e-12) {
    Vec3 axis = Vec3::UnitZ() - Vec3::UnitZ().dot(u) * u;
    if (axis.norm() < 1e-6) axis = Vec3::UnitX() - Vec3::UnitX().dot(u) * u;
    return Eigen::AngleAxisd(M_PI, axis.normalized()).toRotationMatrix();
  }
  return Eigen::Quaterniond::FromTwoVectors(u, v).toRotationMatrix();
}

}  // namespace

std::vector<Eigen::Matrix3d> segment_frames(const MatrixX3& p, bool closed) {
  const int m = segment_count(p, closed);
  std::vector<Eigen::Matrix3d> frames(static_cast<std::size_t>(std::max(m, 0)));
  if (m <= 0) return frames;
  const Vec3 t0 = direction(p, 0);
  Vec3 n = Vec3::Zero();
  for (int i = 1; i < m && n.norm() < 1e-9; ++i) {
    const Vec3 ti = direction(p, i);
    n = ti - ti.dot(t0) * t0;
  }
  if (n.norm() < 1e-9) {  // a straight polygon: the world axis least aligned with t0
    Eigen::Index k;
    t0.cwiseAbs().minCoeff(&k);
    n = Vec3::Unit(k) - Vec3::Unit(k).dot(t0) * t0;
  }
  n.normalize();
  Eigen::Matrix3d F;
  F << t0, n, t0.cross(n);
  frames[0] = F;
  for (int i = 1; i < m; ++i) {
    const Vec3 t = direction(p, i);
    F = least_rotation(F.col(0), t) * F;
    F.col(0) = t;  // keep t exact; n, b re-orthogonalized against it
    F.col(1) = (F.col(1) - F.col(1).dot(t) * t).normalized();
    F.col(2) = t.cross(Vec3(F.col(1)));
    frames[static_cast<std::size_t>(i)] = F;
  }
  return frames;
}

MatrixX3 details_to_frames(const MatrixX3& d, const std::vector<Eigen::Matrix3d>& frames) {
  MatrixX3 out(d.rows(), 3);
  for (Eigen::Index i = 0; i < d.rows(); ++i) out.row(i) = (frames[static_cast<std::size_t>(i)].transpose() * d.row(i).transpose()).transpose();
  return out;
}

MatrixX3 details_from_frames(const MatrixX3& local, const std::vector<Eigen::Matrix3d>& frames) {
  MatrixX3 out(local.rows(), 3);
  for (Eigen::Index i = 0; i < local.rows(); ++i) out.row(i) = (frames[static_cast<std::size_t>(i)] * local.row(i).transpose()).transpose();
  return out;
}

MatrixX3 turn_details(const MatrixX3& detail, const MatrixX3& reference, const MatrixX3& edited, bool closed) {
  MatrixX3 out = detail;
  const Eigen::Index m = edited.rows();
  for (Eigen::Index i = 0; i < detail.rows(); ++i) {
    const Eigen::Index j = (i + 1) % m;
    if (reference.row(i) == edited.row(i) && reference.row(j) == edited.row(j)) continue;  // bit for bit
    out.row(i) = (least_rotation(direction(reference, static_cast<int>(i)), direction(edited, static_cast<int>(i))) *
                  detail.row(i).transpose()).transpose();
  }
  (void)closed;
  return out;
}

}  // namespace fairshape
