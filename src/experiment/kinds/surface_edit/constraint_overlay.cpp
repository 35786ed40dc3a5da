#include "fairshape/experiment/kinds/surface_edit/constraint_overlay.h"

#include "fairshape/io/constraint_overlay.h"

namespace fairshape {

void write_constraint_overlay(const DesignConstraints& placed, const MultiresSurface& edited, const std::string& path) {
  const auto at = [&](int level, int vertex) -> Vec3 { return edited.mesh(level).position(vertex).transpose(); };
  // A surface point is drawn where it is on the edited limit surface: its stencil applied to
  // the edited level (subdivision/limit_evaluation.h).
  const auto on_limit = [&](int level, const SurfacePoint& sp) -> Vec3 {
    return LimitEvaluator::apply(sp.position, edited.mesh(level).positions());
  };
  const auto place = [&](int level, int vertex, const SurfacePoint& sp) {
    return sp.empty() ? at(level, vertex) : on_limit(level, sp);
  };
  ConstraintOverlay overlay;
  for (const PointConstraint& c : placed.points) {
    if (c.offset.norm() > 0) overlay.add_handle(place(c.level, c.vertex, c.surface), c.offset);
    else overlay.add_fixed(place(c.level, c.vertex, c.surface));
  }
  for (const NormalConstraint& c : placed.normals) overlay.add_normal(place(c.level, c.vertex, c.surface), c.normal);
  for (const PlacedCurve& c : placed.curves) {
    std::vector<Vec3> chain;
    for (int v : c.vertices) chain.push_back(at(c.level, v));
    for (const SurfacePoint& sp : c.samples) chain.push_back(on_limit(c.level, sp));
    overlay.add_curve(chain, c.closed);
  }
  overlay.write(path);
}

}  // namespace fairshape
