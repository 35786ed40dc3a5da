#include "fairshape/design/influence.h"

#include <algorithm>

namespace fairshape {

std::vector<int> grow_rings(const SurfaceMesh& mesh, const std::vector<int>& seeds, int rings) {
  std::vector<char> in(static_cast<std::size_t>(mesh.n_vertices()), 0);
  std::vector<int> frontier;
  for (int v : seeds)
    if (!in[v]) in[v] = 1, frontier.push_back(v);
  for (int r = 0; r < rings && !frontier.empty(); ++r) {
    std::vector<int> next;
    for (int v : frontier)
      for (int f : mesh.vertex_faces(v))  // face neighbours: the one-ring a Catmull-Clark stencil sees
        for (int w : mesh.face_vertices(f))
          if (!in[w]) in[w] = 1, next.push_back(w);
    frontier = std::move(next);
  }
  std::vector<int> out;
  for (int v = 0; v < mesh.n_vertices(); ++v)
    if (in[v]) out.push_back(v);
  return out;
}

Eigen::VectorXi reached_on_level(const MultiresSurface& h, int from, const Eigen::VectorXi& moved, int to) {
  Eigen::VectorXi mask = moved;
  for (int l = from; l < to; ++l) {
    const SparseMatrix& S = h.subdivision_operator(l);  // column j: the level-(l+1) vertices vertex j reaches
    std::vector<int> reached;
    for (Eigen::Index j = 0; j < S.outerSize(); ++j) {
      if (!mask(j)) continue;
      for (SparseMatrix::InnerIterator it(S, j); it; ++it)
        if (it.value() != 0) reached.push_back(static_cast<int>(it.row()));
    }
    std::sort(reached.begin(), reached.end());
    reached.erase(std::unique(reached.begin(), reached.end()), reached.end());
    mask = Eigen::VectorXi::Zero(h.mesh(l + 1).n_vertices());
    for (int v : grow_rings(h.mesh(l + 1), reached, 1)) mask(v) = 1;
  }
  return mask;
}

}  // namespace fairshape
