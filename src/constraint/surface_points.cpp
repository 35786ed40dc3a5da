#include "fairshape/constraint/surface_points.h"

#include <limits>

#include "fairshape/constraint/crease_normals.h"
#include "fairshape/constraint/rigid_motion.h"

namespace fairshape {

std::optional<SurfacePointSelection> SurfacePointSelection::from_config(Config& cfg, int level) {
  Config at = cfg.child("at", "a point of the limit surface: {face: F, uv: [u, v], level: L} (a quad's u, v in [0, 1]; "
                              "a Loop triangle's u, v >= 0, u + v <= 1)");
  const int face = at.get_int("face", -1, -1, std::numeric_limits<int>::max(), "face of that level");
  const auto uv = at.get<std::vector<double>>("uv", {}, "parameters [u, v] in the face");
  const int at_level = at.get_int("level", level, -1, 16, "hierarchy level of the face (-1: the finest)");
  at.check_no_unknown_keys();
  const auto nearest = cfg.get<std::vector<double>>(
      "nearest_on_limit", {}, "the point of the limit surface (of `level`) closest to [x, y, z]");
  const bool has_at = cfg.has("at"), has_nearest = cfg.has("nearest_on_limit");
  if (!has_at && !has_nearest) return std::nullopt;
  if (has_at && has_nearest) throw InvalidConfig(cfg.path() + ": give only one of 'at', 'nearest_on_limit'");
  for (const char* key : {"vertices", "nearest", "region", "boundary_loop_near"})
    if (cfg.has(key))
      throw InvalidConfig(cfg.key_path(key) + ": a vertex selection cannot be combined with '" +
                          (has_at ? "at" : "nearest_on_limit") + "' (one point of the limit surface)");
  SurfacePointSelection s;
  if (has_at) {
    if (!at.has("face")) throw InvalidConfig(at.key_path("face") + ": required key is missing (face of that level)");
    if (uv.size() != 2) throw InvalidConfig(at.key_path("uv") + ": expected 2 parameters [u, v]");
    s = SurfacePointSelection::at(at_level, {face, uv[0], uv[1]});
    s.key_ = cfg.key_path("at");
  } else {
    if (nearest.size() != 3) throw InvalidConfig(cfg.key_path("nearest_on_limit") + ": expected 3 coordinates");
    s = SurfacePointSelection::nearest(level, Vec3(nearest[0], nearest[1], nearest[2]));
    s.key_ = cfg.key_path("nearest_on_limit");
  }
  if (cfg.has("on_limit"))
    throw InvalidConfig(cfg.key_path("on_limit") + ": does not apply to a point given by '" +
                        (has_at ? "at" : "nearest_on_limit") + "' (it is on the limit surface already)");
  return s;
}

SurfacePointSelection SurfacePointSelection::at(int level, const FaceParameter& p) {
  SurfacePointSelection s;
  s.level_ = level;
  s.at_ = p;
  return s;
}

SurfacePointSelection SurfacePointSelection::nearest(int level, const Vec3& p) {
  SurfacePointSelection s;
  s.level_ = level;
  s.nearest_ = p;
  s.key_ = "nearest_on_limit";
  return s;
}

SurfacePoint make_surface_point(const LimitEvaluator& evaluator, const FaceParameter& p) {
  SurfacePoint sp;
  sp.at = p;
  sp.corners = evaluator.mesh().face_vertices(p.face);
  LimitStencils s = evaluator.stencils(p);
  sp.position = std::move(s.position);
  sp.du = std::move(s.du);
  sp.dv = std::move(s.dv);
  return sp;
}

std::pair<int, SurfacePoint> SurfacePointSelection::resolve(const LevelMeshes& mesh_at, int finest,
                                                            const SubdivisionOptions& rules, const std::string& who) const {
  const int level = resolve_level(level_, finest, who);
  const LimitEvaluator evaluator(mesh_at(level), rules);
  FaceParameter p;
  if (at_) {
    p = *at_;
    if (std::string why = evaluator.why_not(p); !why.empty())
      throw InvalidInput((key_.rfind(who, 0) == 0 ? key_ : who + "." + key_) + ": on level " + std::to_string(level) +
                         ": " + why);
  } else {
    p = evaluator.closest_point(nearest_);
  }
  return {level, make_surface_point(evaluator, p)};
}

namespace {

// The constrained vertex recorded with a surface point (checks, messages): its face's first corner.
int anchor(const SurfacePoint& sp) { return sp.corners.empty() ? 0 : sp.corners.front(); }

// `position`/`fixed` and `normal` at a surface point differ only in what they ask of the
// point, so one class serves both: it resolves the point once the rules are known, then
// records an offset or a normal there.
class AtSurfacePoint : public Constraint {
 public:
  enum class Asks { Offset, Normal };
  AtSurfacePoint(SurfacePointSelection where, Asks asks, Vec3 value, std::string who,
                 NormalRows rows = NormalRows::Auto)
      : where_(std::move(where)), asks_(asks), value_(value), who_(std::move(who)), rows_(rows) {}
  void add_to(const LevelMeshes&, int, DesignConstraints&) const override {
    throw InvalidInput(who_ + ": a point of the limit surface needs the subdivision rules (add_on_surface)");
  }
  void add_on_surface(const LevelMeshes& mesh_at, int finest, const SubdivisionOptions& rules,
                      DesignConstraints& out) const override {
    auto [level, sp] = where_.resolve(mesh_at, finest, rules, who_);
    // A normal needs a side of a crease; a point given by its face has one, a found one not.
    if (asks_ == Asks::Normal && !where_.face_given())
      refuse_normal_on_crease_point(mesh_at(level), rules, level, sp.at, level < finest, who_);
    const int v = anchor(sp);
    if (asks_ == Asks::Offset) out.points.push_back({level, v, false, value_, who_, std::move(sp)});
    else out.normals.push_back({level, v, value_, who_, std::move(sp), rows_});
  }

 private:
  SurfacePointSelection where_;
  Asks asks_;
  Vec3 value_;  // the offset, or the unit normal
  std::string who_;
  NormalRows rows_;  // a normal's
};

}  // namespace

std::unique_ptr<Constraint> surface_point_offset(SurfacePointSelection where, const Vec3& offset, std::string who) {
  if (!offset.allFinite()) throw InvalidInput(who + ": the offset is not finite");
  return std::make_unique<AtSurfacePoint>(std::move(where), AtSurfacePoint::Asks::Offset, offset, std::move(who));
}

std::unique_ptr<Constraint> surface_point_normal(SurfacePointSelection where, const Vec3& normal, NormalRows rows,
                                                 std::string who) {
  if (!normal.allFinite() || normal.norm() == 0) throw InvalidInput(who + ": the normal is zero or not finite");
  return std::make_unique<AtSurfacePoint>(std::move(where), AtSurfacePoint::Asks::Normal, normal.normalized(),
                                          std::move(who), rows);
}

}  // namespace fairshape
