#include "fairshape/mesh/disjoint_union.h"

namespace fairshape {

SurfaceMesh disjoint_union(const std::vector<SurfaceMesh>& meshes) {
  Eigen::Index n = 0;
  for (const auto& m : meshes) n += m.n_vertices();
  std::map<std::string, Eigen::MatrixXd> arrays;
  if (!meshes.empty())
    for (const auto& [name, data] : meshes.front().vertex_data) {
      bool everywhere = true;
      for (const auto& m : meshes) everywhere &= m.vertex_data.count(name) && m.vertex_data.at(name).cols() == data.cols();
      if (everywhere) arrays[name].resize(n, data.cols());
    }
  MatrixX3 V(n, 3);
  PolygonList faces;
  Eigen::Index offset = 0;
  for (const auto& m : meshes) {
    V.middleRows(offset, m.n_vertices()) = m.positions();
    for (auto& [name, data] : arrays) data.middleRows(offset, m.n_vertices()) = m.vertex_data.at(name);
    for (auto f : m.polygons()) {
      for (int& v : f) v += static_cast<int>(offset);
      faces.push_back(std::move(f));
    }
    offset += m.n_vertices();
  }
  SurfaceMesh out = SurfaceMesh::from_polygons(V, faces);
  out.vertex_data = std::move(arrays);
  return out;
}

}  // namespace fairshape
