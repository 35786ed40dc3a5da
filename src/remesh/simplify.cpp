#include "fairshape/remesh/simplify.h"

#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <cmath>

#include "fairshape/core/error.h"
#include "fairshape/subdivision/subdivider.h"

namespace fairshape {

using Kernel = CGAL::Simple_cartesian<double>;
using CgalMesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace SMS = CGAL::Surface_mesh_simplification;
namespace PMP = CGAL::Polygon_mesh_processing;

namespace {

CgalMesh to_cgal(const SurfaceMesh& dense) {
  require_triangles(dense, "remesh");
  CgalMesh cm;
  std::vector<CgalMesh::Vertex_index> vs;
  for (int v = 0; v < dense.n_vertices(); ++v)
    vs.push_back(cm.add_vertex(Kernel::Point_3(dense.positions()(v, 0), dense.positions()(v, 1), dense.positions()(v, 2))));
  for (const auto& f : dense.polygons())
    if (cm.add_face(vs[f[0]], vs[f[1]], vs[f[2]]) == CgalMesh::null_face())
      throw InvalidInput("remesh: CGAL refused a face of the dense mesh");
  return cm;
}

SurfaceMesh from_cgal(CgalMesh& cm) {
  cm.collect_garbage();
  MatrixX3 V(static_cast<Eigen::Index>(cm.number_of_vertices()), 3);
  for (auto v : cm.vertices()) {
    const auto& p = cm.point(v);
    V.row(static_cast<Eigen::Index>(v.idx())) << p.x(), p.y(), p.z();
  }
  PolygonList faces;
  for (auto f : cm.faces()) {
    std::vector<int> ids;
    for (auto v : cm.vertices_around_face(cm.halfedge(f))) ids.push_back(static_cast<int>(v.idx()));
    faces.push_back(ids);
  }
  try {
    return SurfaceMesh::from_polygons(V, faces);
  } catch (const Error& e) {
    throw InvalidInput(std::string("remesh: the simplified base mesh is not usable: ") + e.what());
  }
}

}  // namespace

SurfaceMesh simplify_to_faces(const SurfaceMesh& dense, int target_faces) {
  CgalMesh cm = to_cgal(dense);
  // A closed triangle mesh has E = 3F/2 edges; stop at the edge count of the target.
  SMS::Count_stop_predicate<CgalMesh> stop(static_cast<std::size_t>(1.5 * target_faces));
  SMS::edge_collapse(cm, stop);
  return from_cgal(cm);
}

SurfaceMesh isotropic_base(const SurfaceMesh& dense, int target_faces) {
  const CgalMesh input = to_cgal(dense);
  // An equilateral triangle of side L has area √3/4 L²; the remesher keeps edges within
  // [4/5 L, 4/3 L], so the count from the area is only a first guess, corrected once.
  const double area = PMP::area(input);
  double length = std::sqrt(4.0 * area / (std::sqrt(3.0) * target_faces));
  CgalMesh cm;
  for (int attempt = 0; attempt < 3; ++attempt) {
    cm = input;
    PMP::isotropic_remeshing(faces(cm), length, cm, PMP::parameters::number_of_iterations(6));
    const double got = static_cast<double>(cm.number_of_faces());
    if (std::abs(got - target_faces) <= 0.05 * target_faces) break;
    length *= std::sqrt(got / target_faces);
  }
  return from_cgal(cm);
}

}  // namespace fairshape
