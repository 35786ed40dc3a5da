#include "fairshape/remesh/relaxation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>

#include "fairshape/remesh/closest_point.h"

namespace fairshape {

MatrixX3 vertex_normals(const SurfaceMesh& m, const MatrixX3& X) {
  MatrixX3 N = MatrixX3::Zero(X.rows(), 3);
  for (int f = 0; f < m.n_faces(); ++f) {
    const auto vs = m.face_vertices(f);
    Vec3 area = Vec3::Zero();
    for (std::size_t i = 0; i < vs.size(); ++i)
      area += X.row(vs[i]).transpose().cross(X.row(vs[(i + 1) % vs.size()]).transpose());
    for (int v : vs) N.row(v) += area.transpose();
  }
  return N;
}

double mean_edge(const SurfaceMesh& topology, const MatrixX3& X) {
  double sum = 0;
  for (int e = 0; e < topology.n_edges(); ++e)
    sum += (X.row(topology.from_vertex(2 * e)) - X.row(topology.to_vertex(2 * e))).norm();
  return topology.n_edges() ? sum / topology.n_edges() : 0.0;
}

Neighbours neighbours(const SurfaceMesh& m) {
  Neighbours n;
  n.start.push_back(0);
  for (int v = 0; v < m.n_vertices(); ++v) {
    for (int w : m.vertex_neighbors(v)) n.ids.push_back(w);
    n.start.push_back(static_cast<int>(n.ids.size()));
    n.boundary.push_back(m.is_boundary_vertex(v) ? 1 : 0);
  }
  return n;
}

std::vector<double> edge_spread(const SurfaceMesh& topology, const MatrixX3& X, double mean) {
  std::vector<double> s(static_cast<std::size_t>(X.rows()), 1.0);
  for (int e = 0; e < topology.n_edges(); ++e) {
    const int a = topology.from_vertex(2 * e), b = topology.to_vertex(2 * e);
    const double l = (X.row(a) - X.row(b)).norm();
    const double off = l > 0 ? std::max(l / mean, mean / l) : std::numeric_limits<double>::infinity();
    s[a] = std::max(s[a], off);
    s[b] = std::max(s[b], off);
  }
  return s;
}

namespace {

// Per vertex, how many of its faces turn against its normal at `reference` (folds).
std::vector<int> turned_faces(const SurfaceMesh& topology, const MatrixX3& X, const MatrixX3& reference_normals) {
  std::vector<int> n(static_cast<std::size_t>(X.rows()), 0);
  for (int f = 0; f < topology.n_faces(); ++f) {
    const auto vs = topology.face_vertices(f);
    Vec3 area = Vec3::Zero();
    for (std::size_t i = 0; i < vs.size(); ++i)
      area += X.row(vs[i]).transpose().cross(X.row(vs[(i + 1) % vs.size()]).transpose());
    for (int v : vs)
      if (area.dot(reference_normals.row(v).transpose()) < 0) ++n[v];
  }
  return n;
}

}  // namespace

int keep_even_moves(const SurfaceMesh& topology, const MatrixX3& before, MatrixX3& after, double band,
                    bool no_new_folds) {
  const double mean = mean_edge(topology, before);
  const std::vector<double> old = edge_spread(topology, before, mean);
  const MatrixX3 normals = no_new_folds ? vertex_normals(topology, before) : MatrixX3();
  const std::vector<int> old_turned = no_new_folds ? turned_faces(topology, before, normals) : std::vector<int>();
  int reverted = 0;
  // Putting a vertex back changes its neighbours' edges too: repeat until no vertex is worse.
  // Only ever moves vertices back, so it ends (at worst with every vertex back).
  for (bool again = true; again;) {
    again = false;
    const std::vector<double> now = edge_spread(topology, after, mean);
    const std::vector<int> turned = no_new_folds ? turned_faces(topology, after, normals) : std::vector<int>();
    for (int v = 0; v < after.rows(); ++v)
      if ((now[v] > std::max(old[v], band) || (no_new_folds && turned[v] > old_turned[v])) &&
          after.row(v) != before.row(v)) {
        after.row(v) = before.row(v);
        ++reverted;
        again = true;
      }
  }
  return reverted;
}

namespace {

// One umbrella round: each vertex moves half way
// towards its neighbours' centroid within its tangent plane (the normal part would shrink the
// surface off the dense one), is projected back, and keeps the move only if edge_spread does
// not get worse than max(before, band) and no more of its faces turn over.
void round(const SurfaceMesh& topology, const Neighbours& nb, MatrixX3& X, const ClosestPointQuery& dense,
           const RelaxSettings& s, int* unmoved, const std::vector<int>* pins) {
  auto still = [&](int v) { return nb.boundary[v] || (pins && (*pins)[v] >= 0) || nb.start[v + 1] == nb.start[v]; };
  const MatrixX3 N = vertex_normals(topology, X);
  MatrixX3 Y = X;
  for (int v = 0; v < X.rows(); ++v) {
    if (still(v)) continue;
    Vec3 c = Vec3::Zero();
    for (int i = nb.start[v]; i < nb.start[v + 1]; ++i) c += X.row(nb.ids[i]).transpose();
    Vec3 d = c / (nb.start[v + 1] - nb.start[v]) - X.row(v).transpose();
    const double len = N.row(v).norm();
    if (len > 0) {
      const Vec3 n = N.row(v).transpose() / len;
      d -= d.dot(n) * n;
    }
    Y.row(v) += 0.5 * d.transpose();
  }
  MatrixX3 Z = dense.facing_points(Y, N, s.reach, unmoved);
  for (int v = 0; v < X.rows(); ++v)
    if (still(v) && !nb.boundary[v]) Z.row(v) = X.row(v);  // pinned: on a dense vertex already
  // Nor may it turn more of the vertex's faces against its normal: a slide that folds the
  // level is undone (cow, 600 faces, 4 levels: edges with faces at >150°, 600 -> 178).
  keep_even_moves(topology, X, Z, s.band, true);
  X = std::move(Z);
}

}  // namespace

void relax(const SurfaceMesh& topology, MatrixX3& X, const ClosestPointQuery& dense, const RelaxSettings& s,
           int* unmoved, const std::vector<int>* pins) {
  const Neighbours nb = neighbours(topology);
  for (int r = 0; r < s.rounds; ++r) round(topology, nb, X, dense, s, unmoved, pins);
}

}  // namespace fairshape
