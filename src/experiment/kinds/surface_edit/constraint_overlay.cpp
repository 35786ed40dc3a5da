#include "experiment/kinds/surface_edit/constraint_overlay.h"

#include <map>

#include "io/vtk_io.h"

namespace fairshape {

void write_constraint_overlay(const DesignConstraints& placed, const MultiresSurface& edited, const std::string& path) {
  const std::size_t n = placed.points.size() + placed.normals.size();
  MatrixX3 points(static_cast<Eigen::Index>(n), 3);
  Eigen::MatrixXd kind(static_cast<Eigen::Index>(n), 1), offset = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), 3),
      normal = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), 3);
  std::map<std::pair<int, int>, int> index;  // (level, vertex) of a point constraint -> its row
  Eigen::Index r = 0;
  for (const PointConstraint& c : placed.points) {
    points.row(r) = edited.mesh(c.level).position(c.vertex).transpose();
    const bool moves = c.offset.norm() > 0;
    kind(r, 0) = moves ? 1 : 0;
    offset.row(r) = c.offset.transpose();
    index.emplace(std::make_pair(c.level, c.vertex), static_cast<int>(r));
    ++r;
  }
  for (const NormalConstraint& c : placed.normals) {
    points.row(r) = edited.mesh(c.level).position(c.vertex).transpose();
    kind(r, 0) = 2;
    normal.row(r) = c.normal.normalized().transpose();
    ++r;
  }
  std::vector<std::vector<int>> curves;
  for (const PlacedCurve& c : placed.curves) {
    std::vector<int> line;
    for (int v : c.vertices) line.push_back(index.at({c.level, v}));
    if (c.closed && !line.empty()) line.push_back(line.front());
    curves.push_back(std::move(line));
  }
  write_vtp(points, curves, {{"kind", kind}, {"offset", offset}, {"target_normal", normal}}, path);
}

}  // namespace fairshape
