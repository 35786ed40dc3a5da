#include "fairshape/constraint/vertex_selection.h"

#include <algorithm>
#include <limits>

namespace fairshape {

VertexSelection VertexSelection::from_config(Config& cfg) {
  VertexSelection s;
  s.ids_ = cfg.get<std::vector<int>>("vertices", {}, "explicit vertex ids");
  s.nearest_ = cfg.get<std::vector<double>>("nearest", {}, "select the vertex closest to [x, y, z]");
  s.loop_near_ = cfg.get<std::vector<double>>("boundary_loop_near", {},
                                               "select the boundary loop closest to [x, y, z]");
  Config region = cfg.child("region", "vertices in a slab of the bounding box: {axis, from, to}");
  static const NameTable<int> axes{{0, "x"}, {1, "y"}, {2, "z"}};
  const int axis = region.get_enum("axis", 0, axes, "slab axis");
  s.from_ = region.get_number("from", 0.0, 0.0, 1.0, "slab start, as a fraction of the box");
  s.to_ = region.get_number("to", 0.0, 0.0, 1.0, "slab end, as a fraction of the box");
  region.check_no_unknown_keys();
  const bool has_region = cfg.has("region");
  if (has_region) s.axis_ = axis;
  if (has_region && s.from_ > s.to_)
    throw InvalidConfig(region.key_path("from") + ": must not exceed 'to'");
  if (!s.nearest_.empty() && s.nearest_.size() != 3)
    throw InvalidConfig(cfg.key_path("nearest") + ": expected 3 coordinates");
  if (!s.loop_near_.empty() && s.loop_near_.size() != 3)
    throw InvalidConfig(cfg.key_path("boundary_loop_near") + ": expected 3 coordinates");
  const int given = !s.ids_.empty() + !s.nearest_.empty() + has_region + !s.loop_near_.empty();
  if (given > 1)
    throw InvalidConfig(cfg.path() + ": give only one of 'vertices', 'nearest', 'region', 'boundary_loop_near'");
  return s;
}

VertexSelection VertexSelection::vertices(std::vector<int> ids) {
  VertexSelection s;
  s.ids_ = std::move(ids);
  return s;
}

VertexSelection VertexSelection::nearest(const Vec3& p) {
  VertexSelection s;
  s.nearest_ = {p.x(), p.y(), p.z()};
  return s;
}

VertexSelection VertexSelection::slab(int axis, double from, double to) {
  if (axis < 0 || axis > 2 || !(from >= 0) || !(to <= 1) || !(from <= to))
    throw InvalidInput("slab selection: axis 0..2 and 0 <= from <= to <= 1");
  VertexSelection s;
  s.axis_ = axis;
  s.from_ = from;
  s.to_ = to;
  return s;
}

VertexSelection VertexSelection::boundary_loop_near(const Vec3& p) {
  VertexSelection s;
  s.loop_near_ = {p.x(), p.y(), p.z()};
  return s;
}

std::vector<int> VertexSelection::resolve(const SurfaceMesh& mesh, const std::string& who) const {
  std::vector<int> out;
  const int nv = mesh.n_vertices();
  for (int id : ids_) {
    if (id < 0 || id >= nv)
      throw InvalidInput(who + ": vertex " + std::to_string(id) + " does not exist (mesh has " +
                         std::to_string(nv) + " vertices)");
    out.push_back(id);
  }
  if (nearest_.size() == 3) {
    const Eigen::RowVector3d p(nearest_[0], nearest_[1], nearest_[2]);
    Eigen::Index best = 0;
    (mesh.positions().rowwise() - p).rowwise().squaredNorm().minCoeff(&best);
    out.push_back(static_cast<int>(best));
  }
  if (loop_near_.size() == 3) {
    const Eigen::RowVector3d p(loop_near_[0], loop_near_[1], loop_near_[2]);
    const auto loops = mesh.boundary_loops();
    if (loops.empty()) throw InvalidInput(who + ": boundary_loop_near: the mesh has no boundary");
    std::size_t best_loop = 0;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < loops.size(); ++k)
      for (int v : loops[k])
        if (const double d = (mesh.positions().row(v) - p).squaredNorm(); d < best) {
          best = d;
          best_loop = k;
        }
    out.insert(out.end(), loops[best_loop].begin(), loops[best_loop].end());
  }
  if (axis_ >= 0) {
    const double lo = mesh.positions().col(axis_).minCoeff(), hi = mesh.positions().col(axis_).maxCoeff();
    for (int v = 0; v < nv; ++v) {
      const double t = hi > lo ? (mesh.positions()(v, axis_) - lo) / (hi - lo) : 0.0;
      if (t >= from_ && t <= to_) out.push_back(v);
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  if (out.empty()) throw InvalidInput(who + ": selects no vertex");
  return out;
}

}  // namespace fairshape
