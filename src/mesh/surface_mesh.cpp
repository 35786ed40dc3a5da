#include "fairshape/mesh/surface_mesh.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "fairshape/core/error.h"

namespace fairshape {
namespace {

std::string face_name(int f) { return "face " + std::to_string(f); }
std::string edge_name(int a, int b) {
  return "edge (" + std::to_string(a) + ", " + std::to_string(b) + ")";
}

void check_input(const MatrixX3& V, const PolygonList& faces) {
  if (V.rows() == 0) throw InvalidInput("mesh has no vertices");
  if (faces.empty()) throw InvalidInput("mesh has no faces");
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if (!V.row(v).allFinite())
      throw InvalidInput("vertex " + std::to_string(v) + " has a NaN or infinite coordinate");
  const int nv = static_cast<int>(V.rows());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto& poly = faces[f];
    const int fi = static_cast<int>(f);
    if (poly.size() < 3)
      throw InvalidInput(face_name(fi) + " has " + std::to_string(poly.size()) +
                         " vertices (a face needs at least 3)");
    for (int v : poly)
      if (v < 0 || v >= nv)
        throw InvalidInput(face_name(fi) + " references vertex " + std::to_string(v) +
                           ", out of range [0, " + std::to_string(nv) + ")");
    std::vector<int> sorted = poly;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      throw InvalidInput(face_name(fi) + " repeats a vertex");
  }
}

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}

}  // namespace

SurfaceMesh SurfaceMesh::from_polygons(const MatrixX3& V, const PolygonList& faces) {
  check_input(V, faces);
  SurfaceMesh m;
  m.positions_ = V;
  const int nv = static_cast<int>(V.rows());
  const int nf = static_cast<int>(faces.size());

  // Pass 1: more than two faces on an undirected edge is non-manifold.
  std::unordered_map<std::uint64_t, int> edge_of;
  std::vector<int> faces_on_edge;
  for (const auto& poly : faces) {
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const int a = poly[i], b = poly[(i + 1) % poly.size()];
      auto [it, inserted] = edge_of.try_emplace(edge_key(a, b), static_cast<int>(faces_on_edge.size()));
      if (inserted) faces_on_edge.push_back(0);
      if (++faces_on_edge[it->second] > 2)
        throw TopologyError(edge_name(a, b) + " is shared by more than two faces (non-manifold edge)");
    }
  }

  // Pass 2: half-edge pairs; half-edge 2e runs from the smaller to the larger vertex id.
  const int ne = static_cast<int>(faces_on_edge.size());
  m.to_vertex_.assign(2 * ne, -1);
  m.face_.assign(2 * ne, -1);
  m.next_.assign(2 * ne, -1);
  m.prev_.assign(2 * ne, -1);
  m.vertex_halfedge_.assign(nv, -1);
  m.face_halfedge_.assign(nf, -1);
  for (int f = 0; f < nf; ++f) {
    const auto& poly = faces[f];
    const int k = static_cast<int>(poly.size());
    std::vector<int> hs(k);
    for (int i = 0; i < k; ++i) {
      const int a = poly[i], b = poly[(i + 1) % k];
      const int e = edge_of.at(edge_key(a, b));
      const int h = a < b ? 2 * e : 2 * e + 1;
      if (m.face_[h] >= 0)
        throw TopologyError(face_name(f) + " and " + face_name(m.face_[h]) + " traverse " +
                            edge_name(a, b) + " in the same direction (inconsistent orientation)");
      m.to_vertex_[h] = b;
      m.to_vertex_[h ^ 1] = a;
      m.face_[h] = f;
      hs[i] = h;
    }
    for (int i = 0; i < k; ++i) {
      m.next_[hs[i]] = hs[(i + 1) % k];
      m.prev_[hs[(i + 1) % k]] = hs[i];
    }
    m.face_halfedge_[f] = hs[0];
  }

  // Pass 3: link boundary half-edges into loops; two boundary fans at one vertex is non-manifold.
  for (int h = 0; h < 2 * ne; ++h) {
    const int v = m.from_vertex(h);
    if (m.face_[h] < 0) {
      if (m.vertex_halfedge_[v] >= 0 && m.face_[m.vertex_halfedge_[v]] < 0)
        throw TopologyError("vertex " + std::to_string(v) +
                            " joins several boundary fans (non-manifold vertex)");
      m.vertex_halfedge_[v] = h;
    } else if (m.vertex_halfedge_[v] < 0) {
      m.vertex_halfedge_[v] = h;
    }
  }
  for (int h = 0; h < 2 * ne; ++h) {
    if (m.face_[h] >= 0) continue;
    const int nh = m.vertex_halfedge_[m.to_vertex_[h]];
    m.next_[h] = nh;
    m.prev_[nh] = h;
  }

  // Pass 4: one fan per vertex; closed fans glued at a vertex are non-manifold too.
  std::vector<int> outgoing(nv, 0);
  for (int h = 0; h < 2 * ne; ++h) ++outgoing[m.from_vertex(h)];
  for (int v = 0; v < nv; ++v) {
    if (m.vertex_halfedge_[v] < 0) continue;
    const int reached = static_cast<int>(m.outgoing_halfedges(v).size());
    if (reached != outgoing[v])
      throw TopologyError("vertex " + std::to_string(v) + " has " + std::to_string(outgoing[v]) +
                          " edges but its fan reaches only " + std::to_string(reached) +
                          " (non-manifold vertex)");
  }
  return m;
}

SurfaceMesh SurfaceMesh::from_halfedge_arrays(MatrixX3 V, HalfedgeArrays a) {
  const std::size_t nh = a.to_vertex.size();
  FAIRSHAPE_ASSERT(nh % 2 == 0 && a.next.size() == nh && a.prev.size() == nh && a.face.size() == nh &&
                       a.vertex_halfedge.size() == static_cast<std::size_t>(V.rows()),
                   "inconsistent half-edge arrays");
  SurfaceMesh m;
  m.positions_ = std::move(V);
  m.to_vertex_ = std::move(a.to_vertex);
  m.next_ = std::move(a.next);
  m.prev_ = std::move(a.prev);
  m.face_ = std::move(a.face);
  m.vertex_halfedge_ = std::move(a.vertex_halfedge);
  m.face_halfedge_ = std::move(a.face_halfedge);
  return m;
}

bool SurfaceMesh::is_boundary_vertex(int v) const {
  const int h = vertex_halfedge_[v];
  return h >= 0 && face_[h] < 0;
}

std::vector<int> SurfaceMesh::outgoing_halfedges(int v) const {
  std::vector<int> out;
  const int start = vertex_halfedge_[v];
  if (start < 0) return out;
  int h = start;
  do {
    out.push_back(h);
    h = rotate_ccw(h);
  } while (h != start && out.size() <= to_vertex_.size());
  return out;
}

int SurfaceMesh::valence(int v) const { return static_cast<int>(outgoing_halfedges(v).size()); }

std::vector<int> SurfaceMesh::vertex_neighbors(int v) const {
  std::vector<int> out;
  for (int h : outgoing_halfedges(v)) out.push_back(to_vertex_[h]);
  return out;
}

std::vector<int> SurfaceMesh::vertex_faces(int v) const {
  std::vector<int> out;
  for (int h : outgoing_halfedges(v))
    if (face_[h] >= 0) out.push_back(face_[h]);
  return out;
}

int SurfaceMesh::face_size(int f) const {
  int n = 0, h = face_halfedge_[f];
  do {
    ++n;
    h = next_[h];
  } while (h != face_halfedge_[f]);
  return n;
}

std::vector<int> SurfaceMesh::face_vertices(int f) const {
  std::vector<int> out;
  int h = face_halfedge_[f];
  do {
    out.push_back(from_vertex(h));
    h = next_[h];
  } while (h != face_halfedge_[f]);
  return out;
}

PolygonList SurfaceMesh::polygons() const {
  PolygonList out(n_faces());
  for (int f = 0; f < n_faces(); ++f) out[f] = face_vertices(f);
  return out;
}

std::vector<std::vector<int>> SurfaceMesh::boundary_loops() const {
  std::vector<std::vector<int>> loops;
  std::vector<char> seen(to_vertex_.size(), 0);
  for (int h0 = 0; h0 < n_halfedges(); ++h0) {
    if (face_[h0] >= 0 || seen[h0]) continue;
    std::vector<int> loop;
    int h = h0;
    do {
      seen[h] = 1;
      loop.push_back(from_vertex(h));
      h = next_[h];
    } while (h != h0);
    loops.push_back(std::move(loop));
  }
  return loops;
}

}  // namespace fairshape

namespace fairshape {

int SurfaceMesh::find_edge(int a, int b) const {
  if (a < 0 || b < 0 || a >= n_vertices() || b >= n_vertices() || is_isolated(a)) return -1;
  int found = -1;
  for_each_outgoing(a, [&](int h) {
    if (to_vertex(h) == b) found = edge(h);
  });
  return found;
}

namespace {
float checked_sharpness(double s, const std::string& what) {
  if (!std::isfinite(s) || s < 0)
    throw InvalidInput(what + ": sharpness must be finite and >= 0, got " + std::to_string(s));
  return static_cast<float>(s);
}
}  // namespace

void SurfaceMesh::set_edge_sharpness(int a, int b, double s) {
  const std::string what = "crease " + std::to_string(a) + "-" + std::to_string(b);
  const float value = checked_sharpness(s, what);
  const int e = find_edge(a, b);
  if (e < 0)
    throw InvalidInput(what + ": the mesh has no edge between vertices " + std::to_string(a) + " and " +
                       std::to_string(b) + " (" + std::to_string(n_vertices()) + " vertices, ids from 0)");
  if (edge_sharpness_.empty()) edge_sharpness_.assign(n_edges(), 0.0f);
  edge_sharpness_[e] = value;
}

void SurfaceMesh::set_vertex_sharpness(int v, double s) {
  const std::string what = "corner " + std::to_string(v);
  const float value = checked_sharpness(s, what);
  if (v < 0 || v >= n_vertices())
    throw InvalidInput(what + ": vertex id out of range (" + std::to_string(n_vertices()) + " vertices, ids from 0)");
  if (vertex_sharpness_.empty()) vertex_sharpness_.assign(n_vertices(), 0.0f);
  vertex_sharpness_[v] = value;
}

void SurfaceMesh::set_sharpness(std::vector<float> edges, std::vector<float> vertices) {
  if (!edges.empty() && static_cast<int>(edges.size()) != n_edges())
    throw InvalidInput("set_sharpness: " + std::to_string(edges.size()) + " edge values for " +
                       std::to_string(n_edges()) + " edges");
  if (!vertices.empty() && static_cast<int>(vertices.size()) != n_vertices())
    throw InvalidInput("set_sharpness: " + std::to_string(vertices.size()) + " vertex values for " +
                       std::to_string(n_vertices()) + " vertices");
  edge_sharpness_ = std::move(edges);
  vertex_sharpness_ = std::move(vertices);
}

}  // namespace fairshape
