// The `fixed` and `position` constraints: selected vertices of one level (the finest unless
// `level` says otherwise) keep their place or move by an offset.
#include "fairshape/constraint/constraint_factories.h"
#include "fairshape/constraint/rigid_motion.h"
#include "fairshape/constraint/surface_points.h"
#include "fairshape/constraint/vertex_selection.h"
#include "fairshape/subdivision/limit.h"

namespace fairshape {
namespace {

class PositionConstraint : public Constraint {
 public:
  PositionConstraint(VertexSelection sel, Vec3 offset, int level, bool on_limit, std::string who)
      : selection_(std::move(sel)), offset_(offset), level_(level), on_limit_(on_limit), who_(std::move(who)) {}

  void add_to(const LevelMeshes& mesh_at, int finest, DesignConstraints& out) const override {
    const int level = resolve_level(level_, finest, who_);
    for (int v : selection_.resolve(mesh_at(level), who_)) out.points.push_back({level, v, on_limit_, offset_, who_});
  }

  // `on_limit` rows are the vertex limit masks (limit_matrix), exact except at darts and
  // undecayed semi-sharp tags of a creased mesh (vertex_limit_mask_exact). There the vertex's
  // limit point is taken from the exact evaluator instead, as a surface point at the vertex:
  // the constraint then holds on the surface the hierarchy converges to.
  void add_on_surface(const LevelMeshes& mesh_at, int finest, const SubdivisionOptions& rules,
                      DesignConstraints& out) const override {
    const int level = resolve_level(level_, finest, who_);
    const SurfaceMesh& m = mesh_at(level);
    if (!on_limit_ || !m.has_sharpness()) {
      add_to(mesh_at, finest, out);
      return;
    }
    std::unique_ptr<LimitEvaluator> exact;  // built for the first vertex that needs it
    for (int v : selection_.resolve(m, who_)) {
      if (vertex_limit_mask_exact(m, v)) {
        out.points.push_back({level, v, true, offset_, who_});
        continue;
      }
      if (!exact) exact = std::make_unique<LimitEvaluator>(m, rules);
      const FaceParameter at = exact->at_vertex(v);
      if (at.face < 0)
        throw InvalidInput(who_ + ": vertex " + std::to_string(v) + " of level " + std::to_string(level) +
                           " has a sharp feature whose limit needs exact evaluation, but no quad around it (an "
                           "N-gon of the base): select it on level " + std::to_string(level + 1));
      SurfacePoint sp = make_surface_point(*exact, at);
      sp.corners = {v};  // marks the vertex itself
      out.points.push_back({level, v, false, offset_, who_, std::move(sp)});
    }
  }

 private:
  VertexSelection selection_;
  Vec3 offset_;
  int level_;
  bool on_limit_;
  std::string who_;
};

std::unique_ptr<Constraint> make(Config& cfg, bool with_offset) {
  const Vec3 offset =
      with_offset ? get_vec3(cfg, "offset", Vec3::Zero(), "displacement [dx, dy, dz] of the handle") : Vec3::Zero();
  const int level = level_from_config(cfg);
  const bool on_limit = cfg.get<bool>("on_limit", false, "constrain the limit positions of the selected vertices");
  auto surface_point = SurfacePointSelection::from_config(cfg, level);
  VertexSelection selection = VertexSelection::from_config(cfg);
  if (surface_point) return surface_point_offset(std::move(*surface_point), offset, constraint_label(cfg));
  return std::make_unique<PositionConstraint>(std::move(selection), offset, level, on_limit, constraint_label(cfg));
}

}  // namespace

int resolve_level(int level, int finest, const std::string& who) {
  const int l = level < 0 ? finest : level;
  if (l > finest)
    throw InvalidInput(who + ": level " + std::to_string(l) + " is not in the hierarchy (levels 0.." +
                       std::to_string(finest) + ")");
  return l;
}

int level_from_config(Config& cfg) {
  return cfg.get_int("level", -1, -1, 16, "hierarchy level of the selected vertices (-1: the finest)");
}

std::string constraint_label(const Config& cfg) { return cfg.path().empty() ? "constraint" : cfg.path(); }

std::unique_ptr<Constraint> prescribed_offset(VertexSelection selection, const Vec3& offset, int level, bool on_limit,
                                              std::string label) {
  if (!offset.allFinite()) throw InvalidInput(label + ": the offset is not finite");
  return std::make_unique<PositionConstraint>(std::move(selection), offset, level, on_limit, std::move(label));
}

std::unique_ptr<Constraint> make_fixed(Config& cfg) { return make(cfg, false); }
std::unique_ptr<Constraint> make_position(Config& cfg) { return make(cfg, true); }

void register_constraints(ConstraintRegistry& r) {
  for (Backend b : built_backends()) {
    r.add("fixed", b, "selected vertices (or a point of the limit surface: at, nearest_on_limit) keep their rest position (ΔP = 0)", make_fixed);
    r.add("position", b, "selected vertices (or a point of the limit surface: at, nearest_on_limit) move by a given offset (ΔP = offset)", make_position);
    r.add("normal", b, "the surface normal at selected vertices (or at a point of the limit surface) becomes a given direction (§4.2)",
          make_normal);
    r.add("rigid", b, "selected vertices (e.g. a boundary loop) follow a rotation and translation (Figure 9)",
          make_rigid);
#if FAIRSHAPE_WITH_CGAL  // snapping finds closest points through CGAL (remesh/closest_point.h)
    r.add("curve", b,
          "a curve on the surface follows a rigid motion; vertices snapped onto it (Appendix) or, with placement "
          "limit_points, points of the limit surface along it",
          make_curve);
#endif
  }
}

}  // namespace fairshape
