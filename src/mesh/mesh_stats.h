// Summary numbers of a mesh, as printed by `fairshape info`.
#pragma once

#include <map>
#include <string>

#include "fairshape/mesh/surface_mesh.h"

namespace fairshape {

struct MeshStats {
  int vertices = 0, faces = 0, edges = 0, isolated_vertices = 0, components = 0;
  int boundary_loops = 0, euler_characteristic = 0, genus = 0;
  std::map<int, int> polygon_sizes;  // face size -> count
  std::map<int, int> valences;       // vertex valence -> count (isolated vertices excluded)
  Vec3 bbox_min = Vec3::Zero(), bbox_max = Vec3::Zero();
};

//! Genus from chi = 2c - 2g - b over the c connected components (orientable surfaces).
MeshStats compute_stats(const SurfaceMesh& mesh);
std::string format_stats(const MeshStats& s);

// Connected component id per vertex (isolated vertices get their own), and their count.
int connected_components(const SurfaceMesh& mesh, std::vector<int>* component_of_vertex);

}  // namespace fairshape
