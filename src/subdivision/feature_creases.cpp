#include "fairshape/subdivision/feature_creases.h"

#include <Eigen/Geometry>
#include <cmath>

#include "fairshape/core/error.h"
#include "fairshape/subdivision/crease_rules.h"

namespace fairshape {
namespace {

// Newell's normal, unit: well defined for non-planar polygons too.
Vec3 unit_face_normal(const SurfaceMesh& m, int f) {
  Vec3 n = Vec3::Zero();
  const auto vs = m.face_vertices(f);
  for (std::size_t i = 0; i < vs.size(); ++i) n += m.position(vs[i]).cross(m.position(vs[(i + 1) % vs.size()]));
  const double len = n.norm();
  return len > 0 ? Vec3(n / len) : Vec3::Zero();
}

}  // namespace

double dihedral_angle_degrees(const SurfaceMesh& m, int e) {
  if (m.is_boundary_edge(e)) return 0.0;
  const Vec3 a = unit_face_normal(m, m.face(2 * e)), b = unit_face_normal(m, m.face(2 * e + 1));
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI;
}

DetectedCreases mark_feature_creases(SurfaceMesh& m, double degrees) {
  if (!(degrees > 0.0 && degrees < 180.0))
    throw InvalidInput("crease angle must be in (0, 180) degrees, got " + std::to_string(degrees));
  DetectedCreases found;
  for (int e = 0; e < m.n_edges(); ++e)
    if (!m.is_boundary_edge(e) && dihedral_angle_degrees(m, e) > degrees) {
      m.set_edge_sharpness(m.from_vertex(2 * e), m.to_vertex(2 * e), kInfiniteSharpness);
      ++found.edges;
    }
  for (int v = 0; v < m.n_vertices(); ++v) {
    if (m.is_isolated(v) || m.is_boundary_vertex(v)) continue;  // the boundary has its own rules
    int sharp = 0;
    m.for_each_outgoing(v, [&](int h) { sharp += m.edge_sharpness(SurfaceMesh::edge(h)) > 0; });
    if (sharp == 1 || sharp > 2) {
      m.set_vertex_sharpness(v, kInfiniteSharpness);
      ++found.corners;
    }
  }
  return found;
}

}  // namespace fairshape
