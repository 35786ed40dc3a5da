// The `rigid` constraint: selected vertices — typically a boundary loop, Boier-Martin et al.'s
// Figure 9 — follow one rotation and translation; each becomes a point constraint.
#include "fairshape/constraint/constraint_factories.h"
#include "fairshape/constraint/rigid_motion.h"
#include "fairshape/constraint/vertex_selection.h"

namespace fairshape {
namespace {

class RigidConstraint : public Constraint {
 public:
  RigidConstraint(VertexSelection sel, RigidMotion motion, int level, std::string who)
      : selection_(std::move(sel)), motion_(motion), level_(level), who_(std::move(who)) {}

  void add_to(const LevelMeshes& mesh_at, int finest, DesignConstraints& out) const override {
    const int level = resolve_level(level_, finest, who_);
    const SurfaceMesh& mesh = mesh_at(level);
    const std::vector<int> ids = selection_.resolve(mesh, who_);
    Vec3 centroid = Vec3::Zero();
    for (int v : ids) centroid += mesh.position(v);
    centroid /= static_cast<double>(ids.size());
    for (int v : ids) {
      const Vec3 p = mesh.position(v);
      out.points.push_back({level, v, false, motion_.apply(p, centroid) - p, who_});
    }
  }

 private:
  VertexSelection selection_;
  RigidMotion motion_;
  int level_;
  std::string who_;
};

}  // namespace

std::unique_ptr<Constraint> make_rigid(Config& cfg) {
  const int level = level_from_config(cfg);
  RigidMotion motion = RigidMotion::from_config(cfg);
  return std::make_unique<RigidConstraint>(VertexSelection::from_config(cfg), motion, level, constraint_label(cfg));
}

}  // namespace fairshape
