// Child connectivity of one subdivision step (pure bookkeeping, shared by both back ends).
#include "fairshape/core/error.h"
#include "fairshape/subdivision/subdivider.h"

namespace fairshape {

void require_triangles(const SurfaceMesh& mesh, const char* who) {
  for (int f = 0; f < mesh.n_faces(); ++f)
    if (mesh.face_size(f) != 3)
      throw InvalidInput(std::string(who) + ": Loop subdivision needs a triangle mesh, but face " +
                         std::to_string(f) + " has " + std::to_string(mesh.face_size(f)) + " vertices");
}

int child_vertex_count(const SurfaceMesh& m, SchemeType scheme) {
  return m.n_vertices() + m.n_edges() + (scheme == SchemeType::CatmullClark ? m.n_faces() : 0);
}

PolygonList child_faces(const SurfaceMesh& m, SchemeType scheme) {
  const int nv = m.n_vertices(), ne = m.n_edges();
  auto edge_point = [&](int h) { return nv + SurfaceMesh::edge(h); };
  PolygonList out;
  out.reserve(scheme == SchemeType::Loop ? 4 * static_cast<std::size_t>(m.n_faces())
                                         : 4 * static_cast<std::size_t>(m.n_faces()));
  for (int f = 0; f < m.n_faces(); ++f) {
    std::vector<int> hs;
    int h = m.face_halfedge(f);
    do {
      hs.push_back(h);
      h = m.next(h);
    } while (h != m.face_halfedge(f));
    const int k = static_cast<int>(hs.size());
    if (scheme == SchemeType::CatmullClark) {
      const int face_point = nv + ne + f;
      for (int i = 0; i < k; ++i)
        out.push_back({m.from_vertex(hs[i]), edge_point(hs[i]), face_point, edge_point(hs[(i + k - 1) % k])});
    } else {
      const int a = m.from_vertex(hs[0]), b = m.from_vertex(hs[1]), c = m.from_vertex(hs[2]);
      const int ab = edge_point(hs[0]), bc = edge_point(hs[1]), ca = edge_point(hs[2]);
      out.push_back({a, ab, ca});
      out.push_back({ab, b, bc});
      out.push_back({ca, bc, c});
      out.push_back({ab, bc, ca});
    }
  }
  return out;
}

}  // namespace fairshape
