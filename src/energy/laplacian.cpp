#include "fairshape/energy/laplacian.h"

#include <Eigen/Geometry>

#include "fairshape/core/error.h"

namespace fairshape {
namespace {

double cotangent(const Vec3& a, const Vec3& b) {  // cot of the angle between a and b
  const double s = a.cross(b).norm();
  return s > 1e-300 ? a.dot(b) / s : 0.0;
}

double edge_weight(const SurfaceMesh& m, int h, LaplacianWeights weights) {
  if (weights == LaplacianWeights::Uniform) return 1.0;
  double w = 0;
  for (int side : {h, m.twin(h)}) {  // the angle opposite the edge in each incident triangle
    if (m.is_boundary_halfedge(side)) continue;
    if (m.face_size(m.face(side)) != 3)
      throw InvalidInput("cotangent weights need a triangle mesh (face " + std::to_string(m.face(side)) +
                         " has " + std::to_string(m.face_size(m.face(side))) + " vertices)");
    const Vec3 o = m.position(m.to_vertex(m.next(side)));
    w += 0.5 * cotangent(m.position(m.from_vertex(side)) - o, m.position(m.to_vertex(side)) - o);
  }
  return w;
}

}  // namespace

SparseMatrix graph_laplacian(const SurfaceMesh& m, LaplacianWeights weights) {
  Triplets t;
  t.reserve(4 * static_cast<std::size_t>(m.n_edges()));
  for (int e = 0; e < m.n_edges(); ++e) {
    const int h = 2 * e, i = m.from_vertex(h), j = m.to_vertex(h);
    const double w = edge_weight(m, h, weights);
    t.emplace_back(i, j, w);
    t.emplace_back(j, i, w);
    t.emplace_back(i, i, -w);
    t.emplace_back(j, j, -w);
  }
  SparseMatrix L(m.n_vertices(), m.n_vertices());
  L.setFromTriplets(t.begin(), t.end());
  return L;
}

SparseMatrix umbrella_operator(const SurfaceMesh& m) {
  SparseMatrix L = graph_laplacian(m, LaplacianWeights::Uniform);
  Eigen::VectorXd inv_valence(m.n_vertices());
  for (int v = 0; v < m.n_vertices(); ++v) inv_valence[v] = m.is_isolated(v) ? 0.0 : 1.0 / m.valence(v);
  return inv_valence.asDiagonal() * L;
}

}  // namespace fairshape
