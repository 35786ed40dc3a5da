#include "experiment/kinds/surface_edit/constraint_overlay.h"

#include "io/constraint_overlay.h"

namespace fairshape {

void write_constraint_overlay(const DesignConstraints& placed, const MultiresSurface& edited, const std::string& path) {
  const auto at = [&](int level, int vertex) -> Vec3 { return edited.mesh(level).position(vertex).transpose(); };
  ConstraintOverlay overlay;
  for (const PointConstraint& c : placed.points) {
    if (c.offset.norm() > 0) overlay.add_handle(at(c.level, c.vertex), c.offset);
    else overlay.add_fixed(at(c.level, c.vertex));
  }
  for (const NormalConstraint& c : placed.normals) overlay.add_normal(at(c.level, c.vertex), c.normal);
  for (const PlacedCurve& c : placed.curves) {
    std::vector<Vec3> chain;
    for (int v : c.vertices) chain.push_back(at(c.level, v));
    overlay.add_curve(chain, c.closed);
  }
  overlay.write(path);
}

}  // namespace fairshape
