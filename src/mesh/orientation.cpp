#include "fairshape/mesh/orientation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <sstream>

#include <Eigen/Geometry>

#include "fairshape/core/error.h"
#include "fairshape/core/parallel_for.h"

namespace fairshape {

Vec3 vector_area(const SurfaceMesh& mesh, const MatrixX3& positions, int f) {
  Vec3 sum = Vec3::Zero();
  const int h0 = mesh.face_halfedge(f);
  int h = h0;
  do {
    sum += positions.row(mesh.from_vertex(h)).transpose().cross(positions.row(mesh.to_vertex(h)).transpose());
    h = mesh.next(h);
  } while (h != h0);
  return 0.5 * sum;
}

Vec3 area_normal(const SurfaceMesh& mesh, const MatrixX3& positions, int v) {
  Vec3 n = Vec3::Zero();
  for (int f : mesh.vertex_faces(v)) n += vector_area(mesh, positions, f);
  return n;
}

std::string FoldReport::describe() const {
  if (flipped.empty()) return "";
  std::ostringstream os;
  os.precision(4);
  os << flipped.size() << " of " << faces << " faces flipped, around (" << center.x() << ", " << center.y() << ", "
     << center.z() << ")";
  return os.str();
}

namespace {

// Faces 0..n-1 given by their vector areas on both surfaces and their centroids on the result.
template <class RestArea, class ResultArea, class Centroid>
FoldReport compare_faces(int n, const RestArea& rest_area, const ResultArea& result_area, const Centroid& centroid) {
  FoldReport r;
  std::vector<Vec3> rest(static_cast<std::size_t>(n));
  double mean_area = 0;
  for (int f = 0; f < n; ++f) mean_area += (rest[f] = rest_area(f)).norm();
  if (n == 0 || !(mean_area > 0)) return r;
  const double tiny = 1e-12 * mean_area / n;
  double cos_largest = 1;
  for (int f = 0; f < n; ++f) {
    const Vec3 now = result_area(f);
    const double a = rest[f].norm(), b = now.norm();
    if (!(a > tiny) || !(b > tiny)) continue;
    ++r.faces;
    const double c = rest[f].dot(now) / (a * b);
    cos_largest = std::min(cos_largest, c);
    if (c >= 0) continue;
    r.flipped.push_back(f);
    r.center += centroid(f);
  }
  if (!r.flipped.empty()) r.center /= static_cast<double>(r.flipped.size());
  r.largest_turn_deg = std::acos(std::clamp(cos_largest, -1.0, 1.0)) * 180.0 / std::numbers::pi;
  return r;
}

Vec3 triangle_area(const std::array<int, 3>& t, const MatrixX3& p) {
  const Vec3 a = p.row(t[0]).transpose(), b = p.row(t[1]).transpose(), c = p.row(t[2]).transpose();
  return 0.5 * (b - a).cross(c - a);
}

}  // namespace

FoldReport flipped_faces(const SurfaceMesh& mesh, const MatrixX3& result) { return RestFaces(mesh).compare(result); }

namespace {

std::vector<Vec3> vector_areas(const SurfaceMesh& mesh, const MatrixX3& positions) {
  std::vector<Vec3> areas(static_cast<std::size_t>(mesh.n_faces()));
  for_each_range(0, mesh.n_faces(), 1024, [&](const IndexRange<int>& r) {
    for (int f = r.begin(); f < r.end(); ++f) areas[static_cast<std::size_t>(f)] = vector_area(mesh, positions, f);
  });
  return areas;
}

}  // namespace

RestFaces::RestFaces(const SurfaceMesh& mesh) : mesh_(mesh), areas_(vector_areas(mesh, mesh.positions())) {}

FoldReport RestFaces::compare(const MatrixX3& result) const {
  if (result.rows() != mesh_.n_vertices())
    throw InvalidInput("fold check: " + std::to_string(result.rows()) + " positions for a mesh of " +
                       std::to_string(mesh_.n_vertices()) + " vertices");
  const std::vector<Vec3> now = vector_areas(mesh_, result);
  return compare_faces(
      mesh_.n_faces(), [&](int f) { return areas_[static_cast<std::size_t>(f)]; },
      [&](int f) { return now[static_cast<std::size_t>(f)]; },
      [&](int f) {
        Vec3 centroid = Vec3::Zero();
        const std::vector<int> corners = mesh_.face_vertices(f);
        for (int v : corners) centroid += result.row(v).transpose();
        return Vec3(centroid / static_cast<double>(corners.size()));
      });
}

void mark_flipped(SurfaceMesh& mesh, const FoldReport& folds) {
  Eigen::MatrixXd flipped = Eigen::MatrixXd::Zero(mesh.n_vertices(), 1);
  for (int f : folds.flipped)
    for (int v : mesh.face_vertices(f)) flipped(v, 0) = 1.0;
  mesh.vertex_data["flipped"] = flipped;
}

FoldReport flipped_triangles(const std::vector<std::array<int, 3>>& triangles, const MatrixX3& rest, const MatrixX3& result) {
  if (rest.rows() != result.rows())
    throw InvalidInput("fold check: " + std::to_string(result.rows()) + " result positions for " +
                       std::to_string(rest.rows()) + " rest positions");
  for (const auto& t : triangles)
    for (int v : t)
      if (v < 0 || v >= rest.rows()) throw InvalidInput("fold check: corner " + std::to_string(v) + " is not a vertex");
  return compare_faces(
      static_cast<int>(triangles.size()), [&](int f) { return triangle_area(triangles[f], rest); },
      [&](int f) { return triangle_area(triangles[f], result); },
      [&](int f) {
        const auto& t = triangles[f];
        return Vec3((result.row(t[0]) + result.row(t[1]) + result.row(t[2])).transpose() / 3.0);
      });
}

}  // namespace fairshape
