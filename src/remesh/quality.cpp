#include "fairshape/remesh/quality.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "fairshape/remesh/closest_point.h"

namespace fairshape {

MatrixX3 sample_surface(const SurfaceMesh& mesh, double spacing) {
  // Vertices once, points along each edge once, points inside each fan triangle: a shared
  // point is not repeated, which matters on a fine remesh with millions of triangles.
  std::vector<Vec3> pts;
  pts.reserve(static_cast<std::size_t>(mesh.n_vertices() + 2 * mesh.n_faces()));
  auto steps = [spacing](double length) { return std::max(1, static_cast<int>(std::ceil(length / spacing))); };
  for (int v = 0; v < mesh.n_vertices(); ++v)
    if (!mesh.is_isolated(v)) pts.push_back(mesh.position(v));
  for (int e = 0; e < mesh.n_edges(); ++e) {
    const Vec3 a = mesh.position(mesh.from_vertex(2 * e)), b = mesh.position(mesh.to_vertex(2 * e));
    const int n = steps((b - a).norm());
    for (int j = 1; j < n; ++j) pts.push_back(a + (double(j) / n) * (b - a));
  }
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto vs = mesh.face_vertices(f);
    for (std::size_t i = 1; i + 1 < vs.size(); ++i) {
      const Vec3 a = mesh.position(vs[0]), b = mesh.position(vs[i]), c = mesh.position(vs[i + 1]);
      const int n = steps(std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()}));
      if (n < 3) pts.push_back((a + b + c) / 3.0);  // a coarse grid has no interior point
      for (int j = 1; j < n; ++j)
        for (int k = 1; j + k < n; ++k) pts.push_back(a + (double(j) / n) * (b - a) + (double(k) / n) * (c - a));
      // A fan's inner diagonals are sampled too (not mesh edges, so not covered above).
      if (i > 1) {
        const int m = steps((b - a).norm());
        for (int j = 1; j < m; ++j) pts.push_back(a + (double(j) / m) * (b - a));
      }
    }
  }
  MatrixX3 out(static_cast<Eigen::Index>(pts.size()), 3);
  for (std::size_t i = 0; i < pts.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = pts[i].transpose();
  return out;
}

namespace {
double largest_distance(const MatrixX3& samples, const ClosestPointQuery& surface) {
  if (samples.rows() == 0) return 0;
  return (samples - surface.closest_points(samples)).rowwise().norm().maxCoeff();
}
}  // namespace

SurfaceDistance hausdorff_distance(const SurfaceMesh& a, const ClosestPointQuery& on_a, const SurfaceMesh& b,
                                   const ClosestPointQuery& on_b, double spacing) {
  return {largest_distance(sample_surface(a, spacing), on_b), largest_distance(sample_surface(b, spacing), on_a)};
}

EdgeLengthRange edge_length_range(const SurfaceMesh& mesh) {
  EdgeLengthRange r{std::numeric_limits<double>::infinity(), 0.0};
  for (int e = 0; e < mesh.n_edges(); ++e) {
    const double l = (mesh.position(mesh.from_vertex(2 * e)) - mesh.position(mesh.to_vertex(2 * e))).norm();
    if (l < r.shortest) r.shortest = l, r.shortest_id = e;
    if (l > r.longest) r.longest = l, r.longest_id = e;
  }
  return r;
}

ValenceHistogram valence_histogram(const SurfaceMesh& mesh) {
  ValenceHistogram h;
  for (int v = 0; v < mesh.n_vertices(); ++v)
    if (!mesh.is_isolated(v)) ++h[mesh.valence(v)];
  return h;
}

std::string to_string(const ValenceHistogram& h) {
  std::ostringstream s;
  for (const auto& [valence, count] : h) s << (s.tellp() > 0 ? " " : "") << valence << ":" << count;
  return s.str();
}

double bounding_box_diagonal(const SurfaceMesh& mesh) {
  if (mesh.n_vertices() == 0) return 0;
  return (mesh.positions().colwise().maxCoeff() - mesh.positions().colwise().minCoeff()).norm();
}

}  // namespace fairshape
