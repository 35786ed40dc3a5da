#include "fairshape/subdivision/multires_surface.h"

#include <cmath>
#include <limits>

#include <Eigen/Geometry>
#include <filesystem>

#include "fairshape/io/json_io.h"
#include "fairshape/io/vtk_io.h"
#include "fairshape/subdivision/detail_fit.h"
#include "fairshape/subdivision/limit.h"
#include "fairshape/subdivision/subdivider.h"

namespace fairshape {
namespace fs = std::filesystem;
namespace {

MatrixX3 to_local(const Frames& f, const MatrixX3& d) {
  MatrixX3 out(d.rows(), 3);
  out.col(0) = f.t1.cwiseProduct(d).rowwise().sum();
  out.col(1) = f.t2.cwiseProduct(d).rowwise().sum();
  out.col(2) = f.n.cwiseProduct(d).rowwise().sum();
  return out;
}

MatrixX3 to_world(const Frames& f, const MatrixX3& d) {
  return f.t1.array().colwise() * d.col(0).array() + f.t2.array().colwise() * d.col(1).array() +
         f.n.array().colwise() * d.col(2).array();
}

}  // namespace

namespace {

// The frame (t1, t2, n) of vertex v from its limit normal n: local_frames' per-vertex rule,
// shared with the region synthesis so that both give the same numbers.
void vertex_frame(const SurfaceMesh& mesh, int v, Vec3 n, Vec3& t1, Vec3& t2, Vec3& normal) {
  Vec3 t = Vec3::UnitX();
  if (n.squaredNorm() < 0.5) n = Vec3::UnitZ();  // no normal (isolated vertex): world axes
  else if (!mesh.is_isolated(v)) t = mesh.position(mesh.to_vertex(mesh.halfedge(v))) - mesh.position(v);
  t -= t.dot(n) * n;
  if (t.norm() < 1e-300) t = n.unitOrthogonal();
  t.normalize();
  normal = n, t1 = t, t2 = n.cross(t);
}

}  // namespace

Frames local_frames(const SurfaceMesh& mesh, const SubdivisionOptions& opt) {
  Frames f;
  f.n = limit_normals(mesh, opt);
  f.t1.resize(mesh.n_vertices(), 3);
  f.t2.resize(mesh.n_vertices(), 3);
  for (int v = 0; v < mesh.n_vertices(); ++v) {
    Vec3 t1, t2, n;
    vertex_frame(mesh, v, f.n.row(v).transpose(), t1, t2, n);
    f.n.row(v) = n.transpose();
    f.t1.row(v) = t1.transpose();
    f.t2.row(v) = t2.transpose();
  }
  return f;
}

MultiresSurface::MultiresSurface(const SurfaceMesh& base, const SubdivisionOptions& opt, int levels, Backend backend,
                                 const UniformRefineLimits& limits)
    : opt_(opt), backend_(backend) {
  require_backend(backend);
  meshes_ = levels == 0 ? std::vector<SurfaceMesh>{base} : refine_uniform(base, opt, levels, backend, limits, &S_);
  world_.resize(levels + 1);
  local_.resize(levels + 1);
  for (int l = 1; l <= levels; ++l) {
    world_[l] = MatrixX3::Zero(meshes_[l].n_vertices(), 3);
    local_[l] = world_[l];
  }
}

MultiresSurface MultiresSurface::analyze(const SurfaceMesh& base, const MatrixX3& finest,
                                         const SubdivisionOptions& opt, int levels, Backend backend) {
  MultiresSurface h(base, opt, levels, backend);
  if (finest.rows() != h.meshes_.back().n_vertices())
    throw InvalidInput("analyze: " + std::to_string(finest.rows()) + " fine positions, but the base refined " +
                       std::to_string(levels) + " times has " + std::to_string(h.meshes_.back().n_vertices()) +
                       " vertices");
  MatrixX3 X = finest;
  for (int l = levels - 1; l >= 0; --l) {
    const SparseMatrix& S = h.S_[l];
    MatrixX3 coarse;
    try {
      coarse = fit_coarse_points(S, X, backend);
    } catch (const InvalidInput& e) {
      throw InvalidInput(std::string(e.what()) + " (level " + std::to_string(l) + ")");
    }
    h.world_[l + 1] = X - S * coarse;
    h.meshes_[l + 1].positions() = X;
    X = coarse;
  }
  h.meshes_[0].positions() = X;
  for (int l = 1; l <= levels; ++l) {
    SurfaceMesh predicted = h.meshes_[l];
    predicted.positions() = h.S_[l - 1] * h.meshes_[l - 1].positions();
    h.local_[l] = to_local(local_frames(predicted, opt), h.world_[l]);
  }
  return h;
}

const MatrixX3& MultiresSurface::details(int level, DetailSpace space) const {
  if (level < 1 || level > levels())
    throw InvalidInput("details: level " + std::to_string(level) + " outside [1, " + std::to_string(levels()) + "]");
  return space == DetailSpace::World ? world_[level] : local_[level];
}

void MultiresSurface::set_base_positions(const MatrixX3& X0) { set_level_positions(0, X0); }

void MultiresSurface::set_level_positions(int level, const MatrixX3& X) {
  if (level < 0 || level > levels())
    throw InvalidInput("set_level_positions: level " + std::to_string(level) + " outside [0, " +
                       std::to_string(levels()) + "]");
  if (X.rows() != meshes_[level].n_vertices() || !X.allFinite())
    throw InvalidInput("set_level_positions: level " + std::to_string(level) + " needs " +
                       std::to_string(meshes_[level].n_vertices()) + " finite rows");
  meshes_[level].positions() = X;
}

void MultiresSurface::set_level_rows(int level, const std::vector<int>& rows, const MatrixX3& X) {
  if (level < 0 || level > levels())
    throw InvalidInput("set_level_rows: level " + std::to_string(level) + " outside [0, " + std::to_string(levels()) + "]");
  if (X.rows() != static_cast<Eigen::Index>(rows.size()) || !X.allFinite())
    throw InvalidInput("set_level_rows: " + std::to_string(rows.size()) + " finite rows needed");
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i] < 0 || rows[i] >= meshes_[level].n_vertices())
      throw InvalidInput("set_level_rows: vertex " + std::to_string(rows[i]) + " is not on level " + std::to_string(level));
    meshes_[level].positions().row(rows[i]) = X.row(static_cast<Eigen::Index>(i));
  }
}

SparseMatrix MultiresSurface::prolongation(int from, int to) const {
  if (from < 0 || to > levels() || from > to)
    throw InvalidInput("prolongation: levels " + std::to_string(from) + " -> " + std::to_string(to) + " outside the hierarchy");
  SparseMatrix P(meshes_[from].n_vertices(), meshes_[from].n_vertices());
  P.setIdentity();
  for (int l = from; l < to; ++l) P = SparseMatrix(S_[l] * P);
  return P;
}

void MultiresSurface::set_details(int level, const MatrixX3& d, DetailSpace space) {
  const MatrixX3& current = details(level, space);
  if (d.rows() != current.rows() || !d.allFinite())
    throw InvalidInput("set_details: level " + std::to_string(level) + " needs " + std::to_string(current.rows()) +
                       " finite rows");
  (space == DetailSpace::World ? world_ : local_)[level] = d;
}

void MultiresSurface::synthesize_from(int level, DetailSpace keep) {
  for (int l = level; l < levels(); ++l) {
    MatrixX3 predicted = S_[l] * meshes_[l].positions();
    SurfaceMesh& fine = meshes_[l + 1];
    fine.positions() = predicted;
    const Frames frames = local_frames(fine, opt_);
    if (keep == DetailSpace::Local) world_[l + 1] = to_world(frames, local_[l + 1]);
    else local_[l + 1] = to_local(frames, world_[l + 1]);
    fine.positions() = predicted + world_[l + 1];
  }
}

std::vector<std::vector<int>> MultiresSurface::synthesize_region_from(int level, const std::vector<int>& changed,
                                                                       DetailSpace keep, int through) {
  std::vector<std::vector<int>> region(static_cast<std::size_t>(levels() + 1));
  region[static_cast<std::size_t>(level)] = changed;
  if (through < 0 || through > levels()) through = levels();
  for (int l = level; l < through; ++l) {
    const SurfaceMesh& coarse = meshes_[l];
    SurfaceMesh& fine = meshes_[l + 1];
    const int n = fine.n_vertices();
    // The children whose stencil reads a changed vertex (S is column-major: a column lists the
    // children of one parent), then one ring more: a vertex's local frame reads the predicted
    // positions of its one-ring (its limit normal, its first edge).
    std::vector<char> in(static_cast<std::size_t>(n), 0);
    std::vector<int> moved;
    for (int p : region[static_cast<std::size_t>(l)])
      for (SparseMatrix::InnerIterator it(S_[l], p); it; ++it)
        if (!in[static_cast<std::size_t>(it.row())]) in[static_cast<std::size_t>(it.row())] = 1, moved.push_back(static_cast<int>(it.row()));
    std::vector<int> out = moved;
    const auto grow = [&](const std::vector<int>& from, std::vector<int>& into, std::vector<char>& mark) {
      std::vector<int> added;
      for (int v : from)
        fine.for_each_outgoing(v, [&](int h) {
          const int w = fine.to_vertex(h);
          if (!mark[static_cast<std::size_t>(w)]) mark[static_cast<std::size_t>(w)] = 1, added.push_back(w);
        });
      into.insert(into.end(), added.begin(), added.end());
      return added;
    };
    (void)grow(moved, out, in);
    // Predicted positions on the region and its one-ring (the normals read them), the old
    // positions of that ring kept to be put back exactly.
    std::vector<char> ring_mark = in;
    std::vector<int> ring;
    (void)grow(out, ring, ring_mark);
    if (S_rows_.size() <= static_cast<std::size_t>(l)) S_rows_.resize(static_cast<std::size_t>(levels()));
    if (S_rows_[l].rows() == 0) S_rows_[l] = S_[l];
    const auto predict = [&](int v) {
      Vec3 p = Vec3::Zero();
      for (RowMajorSparse::InnerIterator it(S_rows_[l], v); it; ++it) p += it.value() * coarse.positions().row(it.col()).transpose();
      return p;
    };
    MatrixX3 kept(static_cast<Eigen::Index>(ring.size()), 3);
    for (std::size_t i = 0; i < ring.size(); ++i) kept.row(static_cast<Eigen::Index>(i)) = fine.positions().row(ring[i]);
    MatrixX3 predicted(static_cast<Eigen::Index>(out.size()), 3);
    for (std::size_t i = 0; i < out.size(); ++i) predicted.row(static_cast<Eigen::Index>(i)) = predict(out[i]).transpose();
    for (std::size_t i = 0; i < out.size(); ++i) fine.positions().row(out[i]) = predicted.row(static_cast<Eigen::Index>(i));
    for (int v : ring) fine.positions().row(v) = predict(v).transpose();
    MatrixX3 world(static_cast<Eigen::Index>(out.size()), 3);
    for (std::size_t i = 0; i < out.size(); ++i) {
      const int v = out[i];
      Vec3 t1, t2, nrm;
      vertex_frame(fine, v, limit_normal_at(fine, opt_, v), t1, t2, nrm);
      if (keep == DetailSpace::Local) {
        const Vec3 d = local_[l + 1].row(v).transpose();
        world_[l + 1].row(v) = (t1 * d.x() + t2 * d.y() + nrm * d.z()).transpose();
      } else {
        const Vec3 d = world_[l + 1].row(v).transpose();
        local_[l + 1].row(v) << t1.dot(d), t2.dot(d), nrm.dot(d);
      }
    }
    for (std::size_t i = 0; i < ring.size(); ++i) fine.positions().row(ring[i]) = kept.row(static_cast<Eigen::Index>(i));
    for (std::size_t i = 0; i < out.size(); ++i)
      fine.positions().row(out[i]) = predicted.row(static_cast<Eigen::Index>(i)) + world_[l + 1].row(out[i]);
    region[static_cast<std::size_t>(l + 1)] = std::move(out);
  }
  return region;
}

void MultiresSurface::save(const std::string& vtm_path) const {
  std::vector<SurfaceMesh> blocks = meshes_;
  std::vector<NamedMesh> named;
  for (int l = 0; l <= levels(); ++l) {
    const int nv = blocks[l].n_vertices();
    blocks[l].vertex_data["detail"] = l ? Eigen::MatrixXd(world_[l]) : Eigen::MatrixXd::Zero(nv, 3);
    blocks[l].vertex_data["detail_local"] = l ? Eigen::MatrixXd(local_[l]) : Eigen::MatrixXd::Zero(nv, 3);
    blocks[l].vertex_data["detail_norm"] = blocks[l].vertex_data["detail"].rowwise().norm();
  }
  for (int l = 0; l <= levels(); ++l) named.push_back({"level_" + std::to_string(l), &blocks[l]});
  const fs::path p(vtm_path);
  write_json({{"format", "fairshape multiresolution surface"},
              {"scheme", to_string(opt_.scheme)},
              {"boundary", to_string(opt_.boundary)},
              {"weights", to_string(opt_.weights)},
              {"crease_method", to_string(opt_.crease)},
              {"levels", levels()}},
             (p.parent_path() / (p.stem().string() + ".json")).string());
  write_vtm(named, vtm_path);
}

MultiresSurface::Stored MultiresSurface::stored(const std::string& vtm_path) {
  const fs::path p(vtm_path);
  const fs::path sidecar = p.parent_path() / (p.stem().string() + ".json");
  if (!fs::exists(sidecar))
    throw InvalidInput(vtm_path + ": not a fairshape hierarchy (no " + sidecar.filename().string() +
                       " beside it; `fairshape remesh` and runs' _levels.vtm write one)");
  const auto meta = read_json(sidecar.string());
  Stored s;
  try {
    if (meta.at("format").get<std::string>() != "fairshape multiresolution surface")
      throw InvalidInput(vtm_path + ": its sidecar is not a fairshape hierarchy's");
    s.options = {scheme_from_string(meta.at("scheme").get<std::string>()),
                 boundary_from_string(meta.at("boundary").get<std::string>()),
                 loop_weights_from_string(meta.at("weights").get<std::string>()),
                 // hierarchies saved before the crease method was an option used uniform decay
                 crease_method_from_string(meta.value("crease_method", std::string("uniform")))};
    s.levels = meta.at("levels").get<int>();
  } catch (const nlohmann::json::exception& e) {
    throw InvalidInput(vtm_path + ": the sidecar JSON lacks scheme options: " + e.what());
  }
  if (s.levels < 0 || s.levels > 16) throw InvalidInput(vtm_path + ": " + std::to_string(s.levels) + " levels, out of 0..16");
  return s;
}

MultiresSurface MultiresSurface::load(const std::string& vtm_path, Backend backend) {
  const Stored st = stored(vtm_path);
  const SubdivisionOptions opt = st.options;
  const auto blocks = read_vtm(vtm_path);
  if (blocks.size() != static_cast<std::size_t>(st.levels) + 1)
    throw InvalidInput(vtm_path + ": holds " + std::to_string(blocks.size()) + " levels (0.." +
                       std::to_string(static_cast<long>(blocks.size()) - 1) + "), but its sidecar declares " +
                       std::to_string(st.levels + 1) + " (0.." + std::to_string(st.levels) + ")");
  MultiresSurface h(blocks[0], opt, static_cast<int>(blocks.size()) - 1, backend);
  for (int l = 1; l <= h.levels(); ++l) {
    const auto it = blocks[l].vertex_data.find("detail");
    if (it == blocks[l].vertex_data.end() || it->second.rows() != h.meshes_[l].n_vertices())
      throw InvalidInput(vtm_path + ": level " + std::to_string(l) + " has no usable 'detail' array");
    h.world_[l] = it->second;
  }
  h.synthesize(DetailSpace::World);
  for (int l = 1; l <= h.levels(); ++l) {
    const double err = (h.meshes_[l].positions() - blocks[l].positions()).cwiseAbs().maxCoeff();
    const double scale = 1.0 + blocks[l].positions().cwiseAbs().maxCoeff();
    if (!(err <= 1e-9 * scale))
      throw InvalidInput(vtm_path + ": level " + std::to_string(l) + " does not match base + details (error " +
                         std::to_string(err) + "): not a hierarchy of this scheme?");
  }
  return h;
}

double relative_detail_change(const MultiresSurface& before, const MultiresSurface& after) {
  double change = 0, size = 0;
  for (int l = 1; l <= before.levels(); ++l) {
    change += (after.details(l, DetailSpace::Local) - before.details(l, DetailSpace::Local)).squaredNorm();
    size += before.details(l, DetailSpace::Local).squaredNorm();
  }
  return size > 0 ? std::sqrt(change / size) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace fairshape
