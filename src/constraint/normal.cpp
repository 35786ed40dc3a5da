// The `normal` constraint (Boier-Martin et al. §4.2): at each selected vertex the surface
// normal becomes the given direction.
#include "fairshape/constraint/constraint_factories.h"
#include "fairshape/constraint/rigid_motion.h"
#include "fairshape/constraint/surface_points.h"
#include "fairshape/constraint/vertex_selection.h"

namespace fairshape {
namespace {

class NormalDirection : public Constraint {
 public:
  NormalDirection(VertexSelection sel, Vec3 normal, NormalRows rows, int level, std::string who)
      : selection_(std::move(sel)), normal_(normal), rows_(rows), level_(level), who_(std::move(who)) {}

  void add_to(const LevelMeshes& mesh_at, int finest, DesignConstraints& out) const override {
    const int level = resolve_level(level_, finest, who_);
    for (int v : selection_.resolve(mesh_at(level), who_)) out.normals.push_back({level, v, normal_, who_, {}, rows_});
  }

 private:
  VertexSelection selection_;
  Vec3 normal_;
  NormalRows rows_;
  int level_;
  std::string who_;
};

}  // namespace

const NameTable<NormalRows>& normal_rows_names() {
  static const NameTable<NormalRows> names{
      {NormalRows::Auto, "auto"}, {NormalRows::Tangent, "tangent"}, {NormalRows::Frame, "frame"}};
  return names;
}

std::unique_ptr<Constraint> make_normal(Config& cfg) {
  cfg.require<std::vector<double>>("normal", "target normal direction [x, y, z] (normalized here)");  // missing: error
  const Vec3 n = cfg.documenting() ? Vec3::UnitZ() : get_vec3(cfg, "normal", Vec3::UnitZ(), "");
  if (n.norm() == 0) throw InvalidConfig(cfg.key_path("normal") + ": must not be zero");
  const NormalRows rows = cfg.get_enum(
      "rows", NormalRows::Auto, normal_rows_names(),
      "how the normal is imposed: tangent (Boier-Martin 4.2's two rows, met by the reverse normal as well), frame "
      "(the rest tangents turned onto the normal), auto (tangent, solved again with frame when the answer is reversed)");
  const int level = level_from_config(cfg);
  auto surface_point = SurfacePointSelection::from_config(cfg, level);
  VertexSelection selection = VertexSelection::from_config(cfg);
  if (surface_point) return surface_point_normal(std::move(*surface_point), n, rows, constraint_label(cfg));
  return std::make_unique<NormalDirection>(std::move(selection), n.normalized(), rows, level, constraint_label(cfg));
}

}  // namespace fairshape
