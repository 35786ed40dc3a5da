#include "fairshape/experiment/kinds/feature/feature_exports.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>
#include <utility>

#include "fairshape/experiment/metric_format.h"
#include "fairshape/feature/curve_on_level.h"
#include "fairshape/feature/level_attachment.h"
#include "fairshape/io/vtk_io.h"
#include "fairshape/subdivision/limit.h"

namespace fairshape {
namespace fs = std::filesystem;

const TableSchema& feature_attachment_table() {
  static const TableSchema t{"attachments", {"feature", "level", "point", "face", "b0", "b1", "b2", "x", "y", "z"}};
  return t;
}

namespace {
// A parameter point of a level on that level's mesh (the face's corners as
// feature::TriangleSurface reads them: from face_halfedge on).
Vec3 point_on(const SurfaceMesh& mesh, const feature::SurfacePoint& p) {
  Vec3 x = Vec3::Zero();
  int h = mesh.face_halfedge(p.face);
  for (int c = 0; c < 3; ++c, h = mesh.next(h)) x += p.bary[c] * mesh.position(mesh.from_vertex(h));
  return x;
}

// One closest-point tree per level of the result, shared by the curves.
class LevelQueries {
 public:
  explicit LevelQueries(const MultiresSurface& result) : result_(result) {}
  const ClosestPointQuery& at(int level) {
    auto& q = queries_[level];
    if (!q) q = std::make_unique<ClosestPointQuery>(result_.mesh(level));
    return *q;
  }

 private:
  const MultiresSurface& result_;
  std::map<int, std::unique_ptr<ClosestPointQuery>> queries_;
};

// Feature `id` on its drawn level (its own faces and coordinates: the definition of the curve,
// §1.4) and on every finer level where the feature is (feature/curve_on_level.h), on the result.
std::vector<CurveOnLevel> curve_on_levels(feature::FeaturedSurface& surface, int id, LevelQueries& queries) {
  const MultiresSurface& result = surface.result();
  double heights = 0;
  for (const auto& [i, f] : surface.features())
    heights += std::max(std::abs(f.params.height), std::abs(f.params.height * f.params.end_height_ratio));
  for (const feature::LevelOperator& op : surface.operators())
    for (std::size_t j = 0; j < op.ids.size(); ++j) {
      if (op.ids[j] != id) continue;
      const feature::BaseCurve& curve = op.curves[j];
      std::vector<CurveOnLevel> out;
      CurveOnLevel drawn{op.level, feature::attachments_per_level(curve, op.level, op.level).front(), {}};
      for (const feature::SurfacePoint& p : drawn.at) drawn.x.push_back(point_on(result.mesh(op.level), p));
      out.push_back(std::move(drawn));
      for (int level = op.level + 1; level <= result.levels(); ++level) {
        const feature::CarriedCurve c = feature::carry_curve(curve, *op.surface, result.mesh(level), queries.at(level),
                                                             feature::carry_reach(curve, heights));
        CurveOnLevel l{level, c.at, {}};
        for (Eigen::Index i = 0; i < c.x.rows(); ++i) l.x.push_back(c.x.row(i).transpose());
        out.push_back(std::move(l));
      }
      return out;
    }
  throw std::logic_error("feature exports: feature " + std::to_string(id) + " has no operator");
}
}  // namespace

std::map<int, std::vector<Vec3>> curves_on_finest_result(feature::FeaturedSurface& surface) {
  LevelQueries queries(surface.result());
  std::map<int, std::vector<Vec3>> out;
  for (const auto& [id, base] : surface.base_curves()) out[id] = curve_on_levels(surface, id, queries).back().x;
  return out;
}

void export_attachments(feature::FeaturedSurface& surface, const RunOutputs& out) {
  LevelQueries queries(surface.result());
  for (const auto& [id, base] : surface.base_curves()) {
    const std::string& name = surface.features().at(id).name;
    for (const CurveOnLevel& l : curve_on_levels(surface, id, queries))
      for (std::size_t i = 0; i < l.at.size(); ++i) {
        const feature::SurfacePoint& p = l.at[i];
        const Vec3& x = l.x[i];
        out.add_row("attachments", {name, std::to_string(l.level), std::to_string(i), std::to_string(p.face), num(p.bary[0]),
                                    num(p.bary[1]), num(p.bary[2]), num(x.x()), num(x.y()), num(x.z())});
      }
  }
}

LimitSurface export_levels_and_limit(feature::FeaturedSurface& surface, const RunOutputs& out) {
  const MultiresSurface& result = surface.result();
  const int finest = result.levels();
  fs::create_directories(fs::path(out.dir) / "levels");
  for (int level = 0; level <= finest; ++level) {
    SurfaceMesh m = result.mesh(level);
    m.vertex_data["feature_displacement"] = surface.perturbation(level).dense(m.n_vertices());
    m.vertex_data["displacement"] = m.positions() - std::as_const(surface).original().mesh(level).positions();
    write_vtp(m, (fs::path(out.dir) / "levels" / (out.run_id + "_level" + std::to_string(level) + ".vtp")).string());
  }
  LimitSurface limit{limit_positions(result.mesh(finest), result.options()), limit_normals(result.mesh(finest), result.options())};
  SurfaceMesh m = result.mesh(finest);
  m.vertex_data["control_position"] = m.positions();
  m.positions() = limit.positions;
  m.vertex_data["limit_normal"] = limit.normals;
  fs::create_directories(fs::path(out.dir) / "limit");
  write_vtp(m, (fs::path(out.dir) / "limit" / (out.run_id + ".vtp")).string());
  return limit;
}

}  // namespace fairshape
