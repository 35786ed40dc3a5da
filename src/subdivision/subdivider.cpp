#include "subdivision/subdivider.h"

#include <cmath>
#include <sstream>

#include "core/error.h"

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

SurfaceMesh subdivide_once(const SurfaceMesh& coarse, const SubdivisionOptions& opt, Backend backend,
                           SparseMatrix* S_out) {
  Refinement r = make_subdivider(backend)->refine(coarse, opt);
  const MatrixX3 fine_positions = r.S * coarse.positions();
  SurfaceMesh fine = SurfaceMesh::from_polygons(fine_positions, r.fine_faces);
  if (S_out) *S_out = std::move(r.S);
  return fine;
}

double estimated_subdivision_bytes(const SurfaceMesh& coarse, SchemeType scheme, int levels) {
  // Each step multiplies faces by ~4 (a k-gon gives k quads); per fine vertex the stored data
  // (positions, half-edges, the operator S) is about 400 bytes, summed over all levels.
  double faces = 0;
  for (int f = 0; f < coarse.n_faces(); ++f) faces += scheme == SchemeType::Loop ? 4 : coarse.face_size(f);
  double total = 0, level_faces = faces;
  for (int l = 1; l <= levels; ++l, level_faces *= 4) total += level_faces * 400.0;
  return total;
}

std::vector<SurfaceMesh> refine_uniform(const SurfaceMesh& base, const SubdivisionOptions& opt, int levels,
                                        Backend backend, const UniformRefineLimits& limits) {
  if (levels < 1 || levels > limits.max_levels)
    throw InvalidInput("levels must be in [1, " + std::to_string(limits.max_levels) + "], got " +
                       std::to_string(levels));
  const double bytes = estimated_subdivision_bytes(base, opt.scheme, levels);
  if (bytes > limits.max_bytes) {
    std::ostringstream os;
    os.precision(3);
    os << levels << " levels of " << to_string(opt.scheme) << " on " << base.n_faces() << " faces need about "
       << bytes / (1 << 30) << " GiB, over the limit of " << limits.max_bytes / (1 << 30)
       << " GiB (raise it with --max-memory-gb)";
    throw InvalidInput(os.str());
  }
  if (opt.scheme == SchemeType::Loop) require_triangles(base, "subdivide");
  std::vector<SurfaceMesh> out{base};
  for (int l = 0; l < levels; ++l) out.push_back(subdivide_once(out.back(), opt, backend));
  return out;
}

}  // namespace fairshape
