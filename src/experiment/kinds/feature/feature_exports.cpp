#include "fairshape/experiment/kinds/feature/feature_exports.h"

#include <filesystem>
#include <utility>

#include "fairshape/experiment/metric_format.h"
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
}  // namespace

std::vector<Vec3> curve_on_finest_result(feature::FeaturedSurface& surface, int id) {
  const MultiresSurface& result = surface.result();
  const feature::BaseCurve& base = surface.base_curves().at(id);
  const auto per_level = feature::attachments_per_level(base, surface.features().at(id).level, result.levels());
  std::vector<Vec3> out;
  for (const feature::SurfacePoint& p : per_level.back()) out.push_back(point_on(result.mesh(result.levels()), p));
  return out;
}

void export_attachments(feature::FeaturedSurface& surface, const RunOutputs& out) {
  const MultiresSurface& result = surface.result();
  const int finest = result.levels();
  for (const auto& [id, base] : surface.base_curves()) {
    const feature::FeatureCurve& curve = surface.features().at(id);
    const auto per_level = feature::attachments_per_level(base, curve.level, finest);
    for (std::size_t k = 0; k < per_level.size(); ++k) {
      const int level = curve.level + static_cast<int>(k);
      const SurfaceMesh& mesh = result.mesh(level);
      for (std::size_t i = 0; i < per_level[k].size(); ++i) {
        const feature::SurfacePoint& p = per_level[k][i];
        const Vec3 x = point_on(mesh, p);
        out.add_row("attachments", {curve.name, std::to_string(level), std::to_string(i), std::to_string(p.face), num(p.bary[0]),
                                    num(p.bary[1]), num(p.bary[2]), num(x.x()), num(x.y()), num(x.z())});
      }
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
