#include "fairshape/io/constraint_overlay.h"

#include "fairshape/io/vtk_io.h"

namespace fairshape {

void ConstraintOverlay::add(const Vec3& at, OverlayKind kind, const Vec3& offset, const Vec3& normal) {
  points_.push_back(at);
  kinds_.push_back(kind);
  offsets_.push_back(offset);
  normals_.push_back(normal);
}

void ConstraintOverlay::add_line(const std::vector<Vec3>& points, bool closed, OverlayKind kind) {
  std::vector<int> line;
  for (const Vec3& p : points) {
    line.push_back(static_cast<int>(points_.size()));
    add(p, kind, Vec3::Zero(), Vec3::Zero());  // a line's point, not a constraint of its own
  }
  if (closed && !line.empty()) line.push_back(line.front());
  lines_.push_back(std::move(line));
}

void ConstraintOverlay::add_curve(const std::vector<Vec3>& points, bool closed) { add_line(points, closed, OverlayKind::CurvePoint); }

void ConstraintOverlay::add_outline(const std::vector<Vec3>& points) { add_line(points, false, OverlayKind::OutlinePoint); }

void ConstraintOverlay::write(const std::string& path) const {
  const auto n = static_cast<Eigen::Index>(points_.size());
  MatrixX3 P(n, 3);
  Eigen::MatrixXd kind(n, 1), offset(n, 3), normal(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    P.row(i) = points_[k].transpose();
    kind(i, 0) = static_cast<int>(kinds_[k]);
    offset.row(i) = offsets_[k].transpose();
    normal.row(i) = normals_[k].transpose();
  }
  write_vtp(P, lines_, {{kOverlayKind, kind}, {kOverlayOffset, offset}, {kOverlayNormal, normal}}, path);
}

}  // namespace fairshape
