#include "fairshape/feature/sparse_loop.h"

#include <algorithm>
#include <numeric>

#include "fairshape/core/error.h"
#include "fairshape/subdivision/subdivider.h"

namespace fairshape::feature {
namespace {

// The child half-edges covering the first and second half of parent half-edge h, as
// refine_topology numbers them (halves of edge e are edges 2e, 2e + 1).
UniformId first_half(UniformId h) { const UniformId e = h >> 1, s = h & 1; return 2 * (2 * e + s) + s; }
UniformId second_half(UniformId h) { const UniformId e = h >> 1, s = h & 1; return 2 * (2 * e + 1 - s) + s; }

}  // namespace

void SparseLevel::index() {
  local_vertex.clear();
  local_face.clear();
  face_of_halfedge.clear();
  local_vertex.reserve(vertex.size());
  local_face.reserve(face.size());
  face_of_halfedge.reserve(3 * face.size());
  for (int v = 0; v < n_local_vertices(); ++v) local_vertex.emplace(vertex[v], v);
  for (int f = 0; f < n_local_faces(); ++f) {
    local_face.emplace(face[f], f);
    for (int i = 0; i < 3; ++i) face_of_halfedge.emplace(halfedges[f][i], f);
  }
  ring_start.assign(vertex.size() + 1, 0);
  for (const auto& c : corners)
    for (int v : c) ++ring_start[v + 1];
  std::partial_sum(ring_start.begin(), ring_start.end(), ring_start.begin());
  ring_faces.assign(static_cast<std::size_t>(ring_start.back()), -1);
  std::vector<int> fill(ring_start.begin(), ring_start.end() - 1);
  for (int f = 0; f < n_local_faces(); ++f)
    for (int v : corners[f]) ring_faces[fill[v]++] = f;
  complete.assign(vertex.size(), 0);
  for (int v = 0; v < n_local_vertices(); ++v) complete[v] = ring_start[v + 1] - ring_start[v] == faces_around[v];
}

int SparseLevel::across(int f, int i) const {
  const auto it = face_of_halfedge.find(halfedges[f][i] ^ 1);
  return it == face_of_halfedge.end() ? -1 : it->second;
}

SparseLevel sparse_base_level(const SurfaceMesh& base) {
  require_triangles(base, "adaptive evaluation");
  SparseLevel s;
  s.n_vertices = base.n_vertices();
  s.n_edges = base.n_edges();
  s.n_faces = base.n_faces();
  s.vertex.resize(static_cast<std::size_t>(base.n_vertices()));
  std::iota(s.vertex.begin(), s.vertex.end(), UniformId{0});
  s.faces_around.assign(static_cast<std::size_t>(base.n_vertices()), 0);
  s.positions = base.positions();
  for (int f = 0; f < base.n_faces(); ++f) {
    std::array<UniformId, 3> h{};
    std::array<int, 3> c{};
    std::uint8_t boundary = 0;
    int e = base.face_halfedge(f);
    for (int i = 0; i < 3; ++i, e = base.next(e)) {
      h[i] = e;
      c[i] = base.from_vertex(e);
      ++s.faces_around[c[i]];
      if (base.is_boundary_halfedge(e ^ 1)) boundary |= std::uint8_t(1u << i);
    }
    s.face.push_back(f);
    s.halfedges.push_back(h);
    s.on_boundary.push_back(boundary);
    s.corners.push_back(c);
  }
  s.index();
  return s;
}

SparsePatch make_patch(const SparseLevel& s) {
  SparsePatch p;
  p.corners.assign(s.face.size(), {-1, -1, -1});
  std::vector<int> faces, group;
  for (int v = 0; v < s.n_local_vertices(); ++v) {
    faces.assign(s.ring_faces.begin() + s.ring_start[v], s.ring_faces.begin() + s.ring_start[v + 1]);
    if (faces.empty()) continue;
    // Fans: faces around v joined when they share an edge at v (a second common corner).
    group.resize(faces.size());
    std::iota(group.begin(), group.end(), 0);
    const auto root = [&](int i) { while (group[i] != i) i = group[i] = group[group[i]]; return i; };
    if (!s.complete[v])
      for (std::size_t i = 0; i < faces.size(); ++i)
        for (std::size_t j = i + 1; j < faces.size(); ++j) {
          int shared = 0;
          for (int a : s.corners[faces[i]])
            for (int b : s.corners[faces[j]]) shared += a == b;
          if (shared >= 2) group[root(static_cast<int>(i))] = root(static_cast<int>(j));
        }
    else
      std::fill(group.begin(), group.end(), 0);
    std::vector<int> copy(faces.size(), -1);
    for (std::size_t i = 0; i < faces.size(); ++i) {
      const int r = root(static_cast<int>(i));
      if (copy[r] < 0) {
        copy[r] = static_cast<int>(p.local.size());
        p.local.push_back(v);
      }
      const auto& c = s.corners[faces[i]];
      for (int k = 0; k < 3; ++k)
        if (c[k] == v) p.corners[faces[i]][k] = copy[r];
    }
  }
  MatrixX3 V(static_cast<Eigen::Index>(p.local.size()), 3);
  for (std::size_t i = 0; i < p.local.size(); ++i) V.row(static_cast<Eigen::Index>(i)) = s.positions.row(p.local[i]);
  PolygonList polys;
  polys.reserve(s.face.size());
  for (const auto& c : p.corners) polys.push_back({c[0], c[1], c[2]});
  p.mesh = SurfaceMesh::from_polygons(V, polys);
  return p;
}

SparseLevel refine_sparse(const SparseLevel& s, const SparsePatch& p, const MatrixX3& Y, const std::vector<int>& refine,
                          const MatrixX3* Y0) {
  SparseLevel t;
  t.level = s.level + 1;
  t.n_vertices = s.n_vertices + s.n_edges;
  t.n_edges = 2 * s.n_edges + 3 * s.n_faces;
  t.n_faces = 4 * s.n_faces;
  std::vector<int> rows;  // the row of Y (and Y0) each new vertex takes
  const auto add_vertex = [&](UniformId id, int faces_around, int row) {
    const auto [it, inserted] = t.local_vertex.try_emplace(id, static_cast<int>(t.vertex.size()));
    if (inserted) {
      t.vertex.push_back(id);
      t.faces_around.push_back(faces_around);
      rows.push_back(row);
    }
    return it->second;
  };
  const int patch_nv = p.mesh.n_vertices();
  for (int f : refine) {
    if (!s.refinable(f)) throw std::logic_error("refine_sparse: face " + std::to_string(s.face[f]) + " is not refinable");
    const auto& H = s.halfedges[f];
    const std::uint8_t B = s.on_boundary[f];
    // Patch half-edge of edge i (corner i → i + 1): the patch face starts at corner 0.
    std::array<int, 3> ph{};
    ph[0] = p.mesh.face_halfedge(f);
    ph[1] = p.mesh.next(ph[0]);
    ph[2] = p.mesh.next(ph[1]);
    std::array<int, 3> corner{}, mid{};
    for (int i = 0; i < 3; ++i) {
      corner[i] = add_vertex(s.vertex[s.corners[f][i]], s.faces_around[s.corners[f][i]], p.corners[f][i]);
      mid[i] = add_vertex(s.n_vertices + (H[i] >> 1), (B >> i) & 1 ? 3 : 6, patch_nv + SurfaceMesh::edge(ph[i]));
    }
    const UniformId interior = 2 * (2 * s.n_edges + 3 * s.face[f]);
    const auto bit = [&](int i) { return std::uint8_t((B >> i) & 1); };
    const auto child = [&](int j, std::array<int, 3> c, std::array<UniformId, 3> h, std::array<std::uint8_t, 3> b) {
      t.face.push_back(4 * s.face[f] + j);
      t.corners.push_back(c);
      t.halfedges.push_back(h);
      t.on_boundary.push_back(std::uint8_t(b[0] | (b[1] << 1) | (b[2] << 2)));
    };
    // As refine_topology: (a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca).
    child(0, {corner[0], mid[0], mid[2]}, {first_half(H[0]), interior + 0, second_half(H[2])}, {bit(0), 0, bit(2)});
    child(1, {mid[0], corner[1], mid[1]}, {second_half(H[0]), first_half(H[1]), interior + 2}, {bit(0), bit(1), 0});
    child(2, {mid[2], mid[1], corner[2]}, {interior + 4, second_half(H[1]), first_half(H[2])}, {0, bit(1), bit(2)});
    child(3, {mid[0], mid[1], mid[2]}, {interior + 3, interior + 5, interior + 1}, {0, 0, 0});
  }
  t.positions.resize(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i) t.positions.row(static_cast<Eigen::Index>(i)) = Y.row(rows[i]);
  if (Y0) {
    t.original.resize(t.positions.rows(), 3);
    for (std::size_t i = 0; i < rows.size(); ++i) t.original.row(static_cast<Eigen::Index>(i)) = Y0->row(rows[i]);
  }
  t.index();
  return t;
}

}  // namespace fairshape::feature
