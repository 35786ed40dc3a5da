#include "fairshape/feature/adaptive_mesh.h"

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

namespace fairshape::feature {
namespace {

// Child k of face f (Loop, child_topology.cpp): corners a, b, c, then the middle one.
int child(int f, int k) { return 4 * f + k; }
int parent(int f) { return f / 4; }

// Angle between the plane of face f (level mesh m) and the line from `mid` to the corner
// opposite the edge of half-edge h.
double midpoint_angle(const SurfaceMesh& m, int h, const Vec3& mid) {
  const Vec3 a = m.position(m.from_vertex(h)), b = m.position(m.to_vertex(h)),
             o = m.position(m.to_vertex(m.next(h)));
  const Vec3 n = (b - a).cross(o - a).normalized();
  const Vec3 line = mid - o;
  return std::asin(std::min(1.0, std::abs(line.dot(n)) / line.norm()));
}

}  // namespace

std::vector<std::array<int, 3>> green_closure(const std::array<int, 3>& corner, const std::array<int, 3>& mid) {
  const int n_mid = (mid[0] >= 0) + (mid[1] >= 0) + (mid[2] >= 0);
  if (n_mid == 0) return {corner};
  if (n_mid == 1) {
    const int i = mid[0] >= 0 ? 0 : mid[1] >= 0 ? 1 : 2;  // edge i: corner i → i + 1
    return {{corner[i], mid[i], corner[(i + 2) % 3]}, {mid[i], corner[(i + 1) % 3], corner[(i + 2) % 3]}};
  }
  if (n_mid == 3) throw std::logic_error("green_closure: a leaf with three midpoints must be split");
  // Two midpoints: the corner between them gets a triangle, the rest a quad cut in two.
  const int j = mid[0] < 0 ? 0 : mid[1] < 0 ? 1 : 2;  // the unsplit edge j: corner j → j + 1
  const int a = corner[j], b = corner[(j + 1) % 3], c = corner[(j + 2) % 3];
  const int mb = mid[(j + 1) % 3], mc = mid[(j + 2) % 3];  // on b→c and c→a
  return {{mb, c, mc}, {a, b, mb}, {a, mb, mc}};
}

AdaptiveMesh adaptive_mesh(const MultiresSurface& s, int from_level, double angle_deg) {
  if (s.options().scheme != SchemeType::Loop) throw InvalidInput("adaptive refinement: the hierarchy is not Loop");
  if (from_level < 0 || from_level > s.levels())
    throw InvalidInput("adaptive refinement: level " + std::to_string(from_level) + " outside 0.." +
                       std::to_string(s.levels()));
  if (!(angle_deg > 0 && angle_deg < 90))
    throw InvalidInput("adaptive refinement: flatness_angle_deg " + std::to_string(angle_deg) + " outside (0, 90)");
  const double threshold = angle_deg * std::numbers::pi / 180;
  const int L = s.levels();
  // split[k][f]: face f of level k is quadrisected.
  std::vector<std::vector<char>> split(static_cast<std::size_t>(L + 1));
  std::vector<std::vector<char>> present(static_cast<std::size_t>(L + 1));
  for (int k = from_level; k <= L; ++k) {
    split[k].assign(static_cast<std::size_t>(s.mesh(k).n_faces()), 0);
    present[k].assign(static_cast<std::size_t>(s.mesh(k).n_faces()), k == from_level);
  }
  const auto edge_flat = [&](int k, int h) {  // both faces of the edge see its midpoint in plane
    const SurfaceMesh& m = s.mesh(k);
    const Vec3 mid = s.mesh(k + 1).position(m.n_vertices() + SurfaceMesh::edge(h));
    for (int side : {h, m.twin(h)})
      if (m.face(side) >= 0 && midpoint_angle(m, side, mid) > threshold) return false;
    return true;
  };
  for (int k = from_level; k < L; ++k) {
    const SurfaceMesh& m = s.mesh(k);
    for (int f = 0; f < m.n_faces(); ++f) {
      if (!present[k][f]) continue;
      int h = m.face_halfedge(f);
      for (int i = 0; i < 3 && !split[k][f]; ++i, h = m.next(h)) split[k][f] = !edge_flat(k, h);
      if (split[k][f])
        for (int c = 0; c < 4; ++c) present[k + 1][child(f, c)] = 1;
    }
  }
  // Balance from fine to coarse: a split face's edge neighbours must exist on its level (their
  // parents split), and a leaf with three hanging midpoints is split itself.
  for (bool changed = true; changed;) {
    changed = false;
    for (int k = L - 1; k >= from_level; --k) {
      const SurfaceMesh& m = s.mesh(k);
      for (int f = 0; f < m.n_faces(); ++f) {
        if (!present[k][f]) continue;
        int hanging = 0;
        int h = m.face_halfedge(f);
        for (int i = 0; i < 3; ++i, h = m.next(h)) {
          const int g = m.face(m.twin(h));
          if (g < 0) continue;
          if (split[k][f] && !present[k][g]) {  // g's parent must be split
            const int pg = parent(g);
            if (k > from_level && !split[k - 1][pg]) {
              split[k - 1][pg] = 1, changed = true;
              for (int c = 0; c < 4; ++c) present[k][child(pg, c)] = 1;
            }
          }
          hanging += present[k][g] && split[k][g] ? 1 : 0;
        }
        if (!split[k][f] && hanging == 3) {
          split[k][f] = 1, changed = true;
          for (int c = 0; c < 4; ++c) present[k + 1][child(f, c)] = 1;
        }
      }
    }
  }
  // Leaves, with green closure towards split neighbours.
  AdaptiveMesh out;
  out.triangles_per_level.assign(static_cast<std::size_t>(L + 1), 0);
  std::vector<int> local(static_cast<std::size_t>(s.mesh(L).n_vertices()), -1);
  PolygonList faces;
  const auto id = [&](int v) {
    if (local[v] < 0) {
      local[v] = static_cast<int>(out.finest_vertex.size());
      out.finest_vertex.push_back(v);
    }
    return local[v];
  };
  for (int k = from_level; k <= L; ++k) {
    const SurfaceMesh& m = s.mesh(k);
    for (int f = 0; f < m.n_faces(); ++f) {
      if (!present[k][f] || (k < L && split[k][f])) continue;
      std::array<int, 3> corner{}, mid{-1, -1, -1};
      int h = m.face_halfedge(f);
      for (int i = 0; i < 3; ++i, h = m.next(h)) {
        corner[i] = m.from_vertex(h);
        const int g = m.face(m.twin(h));
        if (k < L && g >= 0 && present[k][g] && split[k][g]) mid[i] = m.n_vertices() + SurfaceMesh::edge(h);
      }
      for (const auto& t : green_closure(corner, mid)) {
        faces.push_back({id(t[0]), id(t[1]), id(t[2])});
        ++out.triangles_per_level[static_cast<std::size_t>(k)];
      }
    }
  }
  MatrixX3 V(static_cast<Eigen::Index>(out.finest_vertex.size()), 3);
  for (std::size_t i = 0; i < out.finest_vertex.size(); ++i)
    V.row(static_cast<Eigen::Index>(i)) = s.mesh(L).positions().row(out.finest_vertex[i]);
  out.mesh = SurfaceMesh::from_polygons(V, faces);
  return out;
}

}  // namespace fairshape::feature
