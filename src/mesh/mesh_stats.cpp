#include "fairshape/mesh/mesh_stats.h"

#include <numeric>
#include <sstream>

namespace fairshape {

int connected_components(const SurfaceMesh& mesh, std::vector<int>* component_of_vertex) {
  const int nv = mesh.n_vertices();
  std::vector<int> comp(nv, -1);
  int count = 0;
  std::vector<int> stack;
  for (int seed = 0; seed < nv; ++seed) {
    if (comp[seed] >= 0) continue;
    comp[seed] = count;
    stack.push_back(seed);
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      for (int w : mesh.vertex_neighbors(v))
        if (comp[w] < 0) {
          comp[w] = count;
          stack.push_back(w);
        }
    }
    ++count;
  }
  if (component_of_vertex) *component_of_vertex = std::move(comp);
  return count;
}

MeshStats compute_stats(const SurfaceMesh& mesh) {
  MeshStats s;
  s.vertices = mesh.n_vertices();
  s.faces = mesh.n_faces();
  s.edges = mesh.n_edges();
  for (int f = 0; f < s.faces; ++f) ++s.polygon_sizes[mesh.face_size(f)];
  for (int v = 0; v < s.vertices; ++v) {
    if (mesh.is_isolated(v)) ++s.isolated_vertices;
    else ++s.valences[mesh.valence(v)];
  }
  s.boundary_loops = static_cast<int>(mesh.boundary_loops().size());
  const int used_vertices = s.vertices - s.isolated_vertices;
  s.euler_characteristic = used_vertices - s.edges + s.faces;
  s.components = connected_components(mesh, nullptr) - s.isolated_vertices;
  s.genus = (2 * s.components - s.boundary_loops - s.euler_characteristic) / 2;
  s.bbox_min = mesh.positions().colwise().minCoeff().transpose();
  s.bbox_max = mesh.positions().colwise().maxCoeff().transpose();
  return s;
}

std::string format_stats(const MeshStats& s) {
  std::ostringstream os;
  os << "vertices             " << s.vertices;
  if (s.isolated_vertices) os << " (" << s.isolated_vertices << " isolated)";
  os << "\nfaces                " << s.faces << "\nedges                " << s.edges
     << "\ncomponents           " << s.components
     << "\nboundary loops       " << s.boundary_loops
     << "\nEuler characteristic " << s.euler_characteristic
     << "\ngenus                " << s.genus << "\npolygon sizes        ";
  for (auto [k, n] : s.polygon_sizes) os << k << "-gons: " << n << "  ";
  os << "\nvalences             ";
  for (auto [k, n] : s.valences) os << k << ": " << n << "  ";
  os << "\nbounding box         [" << s.bbox_min.transpose() << "] - [" << s.bbox_max.transpose()
     << "]\n";
  return os.str();
}

}  // namespace fairshape
