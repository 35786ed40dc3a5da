#include "remesh/remesh.h"

#include "remesh/closest_point.h"
#include "remesh/simplify.h"
#include "subdivision/subdivider.h"

namespace fairshape {
namespace {

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
  const MatrixX3 projected = on_dense.closest_points(smooth.mesh(opt.levels).positions());
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
  r.bbox_diagonal = (dense.positions().colwise().maxCoeff() - dense.positions().colwise().minCoeff()).norm();
  if (report) *report = r;
  return h;
}

}  // namespace fairshape
