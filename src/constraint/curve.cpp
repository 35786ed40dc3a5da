// The `curve` constraint (Boier-Martin et al. §4.2 and Appendix): a curve drawn on the surface
// moves — rigidly, or to given target points — and the surface follows. The curve is turned
// into point constraints at the vertices snapped onto it, on the first level (from `level`
// up to the finest) where the snapped chain satisfies the approximation property. With
// `placement: limit_points` it becomes point constraints at exact points of one level's limit
// surface instead (curve_limit_points.h), on any level, without the re-parameterization.
#include <sstream>

#include "fairshape/constraint/constraint_factories.h"
#include "fairshape/constraint/curve_limit_points.h"
#include "fairshape/constraint/curve_snapping.h"
#include "fairshape/constraint/rigid_motion.h"
#include <limits>

namespace fairshape {
namespace {

MatrixX3 points_from_config(Config& cfg, const std::string& key, const std::string& doc) {
  const auto rows = cfg.get<std::vector<std::vector<double>>>(key, {}, doc);
  MatrixX3 P(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].size() != 3)
      throw InvalidConfig(cfg.key_path(key) + "[" + std::to_string(i) + "]: expected 3 numbers [x, y, z]");
    P.row(static_cast<Eigen::Index>(i)) << rows[i][0], rows[i][1], rows[i][2];
  }
  if (!P.allFinite()) throw InvalidConfig(cfg.key_path(key) + ": not finite");
  return P;
}

double mean_edge_length(const SurfaceMesh& m) {
  double sum = 0;
  for (int e = 0; e < m.n_edges(); ++e) sum += (m.position(m.to_vertex(2 * e)) - m.position(m.from_vertex(2 * e))).norm();
  return m.n_edges() ? sum / m.n_edges() : 0.0;
}

class CurveConstraint : public Constraint {
 public:
  struct Options {
    MatrixX3 points, targets;  // targets empty: the rigid motion
    bool closed = false;
    RigidMotion motion;
    int first_level = 0;
    double snap_ratio = 0.4, max_distance = 0.01;
    bool limit_points = false;  // placement limit_points
    bool level_given = false;
    double sample_ratio = 2.0;  // limit_points: polygon sampling step × the level's mean edge length (see README)
  };
  CurveConstraint(Options o, std::string who) : o_(std::move(o)), who_(std::move(who)) {}

  void add_on_surface(const LevelMeshes& mesh_at, int finest, const SubdivisionOptions& rules,
                      DesignConstraints& out) const override {
    std::string no_chain;
    if (!o_.limit_points && snap(mesh_at, finest, out, &no_chain)) return;
    // Snapping found no chain of vertices along the curve on any level it may use (on a remeshed
    // scan's finest level the vertices rarely line up): the curve is met exactly on the finest
    // level's limit surface instead, and the run's message says so (papers/boier-martin/README.md,
    // "Curves on the finest level").
    // The surface the designer sees is the finest level's limit: the points go there unless
    // `level` names another level (whose limit surface they then lie on).
    const int level = o_.limit_points ? resolve_level(o_.level_given ? o_.first_level : -1, finest, who_) : finest;
    place_on_limit_surface(mesh_at, finest, rules, level, out);
    if (!o_.limit_points)
      out.curves.back().note = who_ + ": no level from " + std::to_string(resolve_level(o_.first_level, finest, who_)) +
                               " to " + std::to_string(finest) + " has a chain of snapped vertices (" + no_chain +
                               "), so it is placed at points of the finest level's limit surface (placement: limit_points)";
  }

  void add_to(const LevelMeshes& mesh_at, int finest, DesignConstraints& out) const override {
    if (o_.limit_points)
      throw InvalidInput(who_ + ": placement limit_points needs the subdivision rules (add_on_surface)");
    std::string why;
    if (!snap(mesh_at, finest, out, &why))
      throw InvalidInput(who_ + ": no level from " + std::to_string(resolve_level(o_.first_level, finest, who_)) + " to " +
                         std::to_string(finest) + " has a chain of vertices along the curve (" + why +
                         "); use placement: limit_points (exact points of the limit surface, any level), draw the curve "
                         "through finer features, add levels, or raise snap_ratio");
  }

 private:
  void place_on_limit_surface(const LevelMeshes& mesh_at, int finest, const SubdivisionOptions& rules, int level,
                              DesignConstraints& out) const {
    const SurfaceMesh& m = mesh_at(level);
    const LimitEvaluator evaluator(m, rules);
    const SurfaceMesh& fine = mesh_at(finest);
    const double diagonal = (fine.positions().colwise().maxCoeff() - fine.positions().colwise().minCoeff()).norm();
    const LimitCurve c = place_on_limit(evaluator, o_.points, o_.closed, o_.sample_ratio * mean_edge_length(m),
                                        o_.max_distance * diagonal, who_);
    const Vec3 centroid = o_.points.colwise().mean().transpose();
    // The point on the limit moves with the curve: by the polygon's motion at its parameter.
    for (std::size_t i = 0; i < c.points.size(); ++i)
      out.points.push_back({level, c.points[i].corners.front(), false, displacement(c.source[i], centroid), who_, c.points[i]});
    out.curves.push_back({level, {}, o_.closed, who_, c.points});
  }

  // Vertices snapped onto the curve on the first level from `level` where they form a chain
  // (Appendix); false, with the last level's reason in `why`, when none does.
  bool snap(const LevelMeshes& mesh_at, int finest, DesignConstraints& out, std::string* why_none) const {
    const int first = resolve_level(o_.first_level, finest, who_);
    // "Leaves the surface" is judged on the finest level, the surface the designer sees.
    const SurfaceMesh& fine = mesh_at(finest);
    const double diagonal = (fine.positions().colwise().maxCoeff() - fine.positions().colwise().minCoeff()).norm();
    const CurveOnSurface on_fine =
        project_curve(fine, o_.points, o_.closed, 0.25 * mean_edge_length(fine), o_.max_distance * diagonal, who_);
    const Vec3 centroid = o_.points.colwise().mean().transpose();
    std::string why;
    for (int level = first; level <= finest; ++level) {
      const SurfaceMesh& m = mesh_at(level);
      const CurveOnSurface c = level == finest ? on_fine
                                               : project_curve(m, o_.points, o_.closed, 0.25 * mean_edge_length(m),
                                                               std::numeric_limits<double>::infinity(), who_);
      const auto chain = snap_vertices(m, c, o_.snap_ratio, &why);
      if (!chain) continue;
      for (std::size_t i = 0; i < chain->vertices.size(); ++i) {
        const Vec3 target = chain->on_curve[i] + displacement(chain->source[i], centroid);
        out.points.push_back({level, chain->vertices[i], false, target - m.position(chain->vertices[i]), who_});
      }
      out.curves.push_back({level, chain->vertices, o_.closed, who_});
      return true;
    }
    *why_none = why;
    return false;
  }

  // The motion of the control polygon at parameter u (segment + fraction).
  Vec3 displacement(double u, const Vec3& centroid) const {
    const Eigen::Index n = o_.points.rows();
    const Eigen::Index s = std::min<Eigen::Index>(static_cast<Eigen::Index>(u), o_.closed ? n - 1 : n - 2);
    const double f = u - static_cast<double>(s);
    auto at = [&](const MatrixX3& P) -> Vec3 {
      return (1 - f) * P.row(s).transpose() + f * P.row((s + 1) % n).transpose();
    };
    const Vec3 p = at(o_.points);
    return o_.targets.rows() ? Vec3(at(o_.targets) - p) : Vec3(o_.motion.apply(p, centroid) - p);
  }

  Options o_;
  std::string who_;
};

}  // namespace

std::unique_ptr<Constraint> make_curve(Config& cfg) {
  CurveConstraint::Options o;
  o.points = points_from_config(cfg, "points", "the curve's control polygon [[x, y, z], ...], on the surface");
  if (o.points.rows() < 2 && !cfg.documenting())
    throw InvalidConfig(cfg.key_path("points") + ": a curve needs at least 2 points");
  o.closed = cfg.get<bool>("closed", false, "the curve is a closed loop");
  o.targets = points_from_config(cfg, "target_points", "where the control points go (default: the rigid motion)");
  if (o.targets.rows() && o.targets.rows() != o.points.rows())
    throw InvalidConfig(cfg.key_path("target_points") + ": " + std::to_string(o.targets.rows()) +
                        " points for a curve of " + std::to_string(o.points.rows()));
  o.motion = RigidMotion::from_config(cfg);
  if (o.targets.rows() && (cfg.has("rotation") || cfg.has("translation")))
    throw InvalidConfig(cfg.path() + ": give either 'target_points' or a rigid motion ('rotation', 'translation')");
  o.level_given = cfg.has("level");
  o.first_level = cfg.get_int("level", 0, -1, 16,
                              "snap: first level tried, finer levels follow until the chain has no gap; limit_points: the "
                              "level whose limit surface carries the points (default: the finest)");
  static const NameTable<bool> placements{{false, "snap"}, {true, "limit_points"}};
  o.limit_points = cfg.get_enum("placement", false, placements,
                                "snap: vertices snapped onto the curve (Appendix); limit_points: exact points of the "
                                "limit surface along it");
  o.sample_ratio = cfg.get_number("sample_ratio", o.sample_ratio, 0.05, 4.0,
                                  "limit_points: polygon sampling step, × the level's mean edge length (points are added where (AP) needs them)");
  o.snap_ratio = cfg.get_number("snap_ratio", o.snap_ratio, 0.05, 0.5,
                                "a vertex snaps when closer to the curve than this × its shortest edge");
  o.max_distance = cfg.get_number("max_distance", o.max_distance, 0.0, 1.0,
                                  "largest distance of the curve from the surface, × the bounding-box diagonal");
  return std::make_unique<CurveConstraint>(std::move(o), constraint_label(cfg));
}

}  // namespace fairshape
