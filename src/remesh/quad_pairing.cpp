#include "fairshape/remesh/quad_pairing.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "fairshape/subdivision/subdivider.h"

namespace fairshape {
namespace {

double angle_deg(const Vec3& u, const Vec3& v) {
  return std::atan2(u.cross(v).norm(), u.dot(v)) * 180.0 / std::numbers::pi;
}

}  // namespace

SurfaceMesh pair_triangles(const SurfaceMesh& m, const QuadPairing& opt) {
  require_triangles(m, "pair_triangles");
  struct Candidate {
    double score;
    int edge;
  };
  std::vector<Candidate> candidates;
  for (int e = 0; e < m.n_edges(); ++e) {
    if (m.is_boundary_edge(e)) continue;
    // Halfedge a→b in triangle (a, b, c), its twin b→a in (b, a, d): the quad is (a, d, b, c).
    const int h = 2 * e;
    const int a = m.from_vertex(h), b = m.to_vertex(h), c = m.to_vertex(m.next(h)), d = m.to_vertex(m.next(h ^ 1));
    if (c == d) continue;
    const Vec3 pa = m.position(a), pb = m.position(b), pc = m.position(c), pd = m.position(d);
    const Vec3 quad[4] = {pa, pd, pb, pc};
    double worst = 0;
    for (int i = 0; i < 4; ++i)
      worst = std::max(worst, std::abs(angle_deg(quad[(i + 3) % 4] - quad[i], quad[(i + 1) % 4] - quad[i]) - 90.0));
    const double fold = angle_deg((pb - pa).cross(pc - pa), (pa - pb).cross(pd - pb));
    if (worst <= opt.max_corner_deviation_deg && fold <= opt.max_fold_deg) candidates.push_back({worst + 0.5 * fold, e});
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& x, const Candidate& y) { return x.score < y.score || (x.score == y.score && x.edge < y.edge); });
  std::vector<char> used(static_cast<std::size_t>(m.n_faces()), 0);
  // Merging removes the shared edge; a vertex left with two edges would be a degenerate corner
  // of both faces around it, so every vertex keeps at least three (two on a boundary).
  std::vector<int> valence(static_cast<std::size_t>(m.n_vertices()));
  for (int v = 0; v < m.n_vertices(); ++v) valence[v] = m.valence(v) - (m.is_boundary_vertex(v) ? 1 : 0);
  PolygonList faces;
  for (const Candidate& cand : candidates) {
    const int h = 2 * cand.edge;
    const int f = m.face(h), g = m.face(h ^ 1);
    const int a = m.from_vertex(h), b = m.to_vertex(h);
    if (used[f] || used[g] || valence[a] <= 3 || valence[b] <= 3) continue;
    used[f] = used[g] = 1;
    --valence[a];
    --valence[b];
    faces.push_back({m.from_vertex(h), m.to_vertex(m.next(h ^ 1)), m.to_vertex(h), m.to_vertex(m.next(h))});
  }
  for (int f = 0; f < m.n_faces(); ++f)
    if (!used[f]) faces.push_back(m.face_vertices(f));
  return SurfaceMesh::from_polygons(m.positions(), faces);
}

}  // namespace fairshape
