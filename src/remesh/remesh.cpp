#include "remesh/remesh.h"

#include <Eigen/Geometry>
#include <limits>

#include "remesh/closest_point.h"
#include "remesh/simplify.h"
#include "subdivision/subdivider.h"

namespace fairshape {
namespace {

// Closest-point projection bunches vertices up where the dense surface is thin or curved;
// divided differences scale like 1/h², so that wrecks the conditioning of fairness energies.
// A few rounds of tangential umbrella relaxation, each followed by re-projection, even the
// spacing out while keeping every vertex on the dense surface.
MatrixX3 relax_on_surface(const SurfaceMesh& topology, MatrixX3 X, const ClosestPointQuery& surface, int rounds) {
  SurfaceMesh m = topology;
  for (int r = 0; r < rounds; ++r) {
    m.positions() = X;
    MatrixX3 step(X.rows(), 3);
    for (int v = 0; v < m.n_vertices(); ++v) {
      Vec3 centroid = Vec3::Zero(), normal = Vec3::Zero();
      const auto hs = m.outgoing_halfedges(v);
      for (int h : hs) {
        centroid += m.position(m.to_vertex(h));
        if (!m.is_boundary_halfedge(h))
          normal += (m.position(m.to_vertex(h)) - m.position(v)).cross(m.position(m.to_vertex(m.next(h))) - m.position(v));
      }
      Vec3 d = hs.empty() ? Vec3::Zero() : Vec3(centroid / double(hs.size()) - m.position(v));
      if (m.is_boundary_vertex(v)) d.setZero();  // keep boundary curves where they are
      if (normal.norm() > 0) d -= d.dot(normal.normalized()) * normal.normalized();
      step.row(v) = 0.5 * d.transpose();
    }
    X = surface.closest_points(X + step);
  }
  return X;
}

// Largest (and RMS) distance between corresponding rows.
double max_distance(const MatrixX3& from, const MatrixX3& to, double* rms) {
  const Eigen::VectorXd d = (from - to).rowwise().norm();
  if (rms) *rms = std::sqrt(d.squaredNorm() / static_cast<double>(std::max<Eigen::Index>(1, d.size())));
  return d.size() ? d.maxCoeff() : 0.0;
}

}  // namespace

MultiresSurface remesh(const SurfaceMesh& dense, const RemeshOptions& opt, RemeshReport* report) {
  if (opt.base_faces < 4 || opt.base_faces > dense.n_faces())
    throw InvalidInput("remesh: --base-faces " + std::to_string(opt.base_faces) + " outside [4, " +
                       std::to_string(dense.n_faces()) + "] (the dense mesh has " + std::to_string(dense.n_faces()) +
                       " faces)");
  RemeshReport r;
  const SurfaceMesh base = simplify_to_faces(dense, opt.base_faces);
  if (opt.subdivision.scheme == SchemeType::Loop) require_triangles(base, "remesh");
  const MultiresSurface smooth(base, opt.subdivision, opt.levels, opt.backend);
  const ClosestPointQuery on_dense(dense);
  const MatrixX3 projected = relax_on_surface(smooth.mesh(opt.levels),
                                             on_dense.closest_points(smooth.mesh(opt.levels).positions()), on_dense,
                                             opt.relax_rounds);
  if (!projected.allFinite()) throw InvalidInput("remesh: projection onto the dense surface failed (non-finite points)");
  MultiresSurface h = MultiresSurface::analyze(base, projected, opt.subdivision, opt.levels, opt.backend);

  SurfaceMesh fine = h.mesh(opt.levels);
  const ClosestPointQuery on_fine(fine);
  double rms_back = 0;
  const double fine_to_dense = max_distance(projected, on_dense.closest_points(projected), &r.rms_fine_to_dense);
  const double dense_to_fine = max_distance(dense.positions(), on_fine.closest_points(dense.positions()), &rms_back);
  r.hausdorff = std::max(fine_to_dense, dense_to_fine);
  r.base_faces = base.n_faces();
  r.fine_vertices = fine.n_vertices();
  r.shortest_edge = std::numeric_limits<double>::infinity();
  for (int e = 0; e < fine.n_edges(); ++e)
    r.shortest_edge = std::min(r.shortest_edge, (fine.position(fine.from_vertex(2 * e)) - fine.position(fine.to_vertex(2 * e))).norm());
  r.bbox_diagonal = (dense.positions().colwise().maxCoeff() - dense.positions().colwise().minCoeff()).norm();
  if (report) *report = r;
  return h;
}

}  // namespace fairshape
