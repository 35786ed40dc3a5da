#include "fairshape/constraint/curve_snapping.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_map>

#include "fairshape/core/error.h"
#include "fairshape/remesh/closest_point.h"

namespace fairshape {
namespace {

// Vertices bucketed in a uniform grid, for "which vertices are near this segment".
class VertexGrid {
 public:
  VertexGrid(const MatrixX3& V, double cell) : cell_(cell) {
    for (int v = 0; v < V.rows(); ++v) cells_[key(cell_of(V.row(v).transpose()))].push_back(v);
  }
  template <class Visit>
  void near_box(const Vec3& lo, const Vec3& hi, const Visit& visit) const {
    const Eigen::Vector3i a = cell_of(lo), b = cell_of(hi);
    for (int x = a.x(); x <= b.x(); ++x)
      for (int y = a.y(); y <= b.y(); ++y)
        for (int z = a.z(); z <= b.z(); ++z)
          if (auto it = cells_.find(key({x, y, z})); it != cells_.end())
            for (int v : it->second) visit(v);
  }

 private:
  Eigen::Vector3i cell_of(const Vec3& p) const { return (p / cell_).array().floor().cast<int>(); }
  static std::int64_t key(const Eigen::Vector3i& c) {
    return (static_cast<std::int64_t>(c.x()) * 73856093) ^ (static_cast<std::int64_t>(c.y()) * 19349663) ^
           (static_cast<std::int64_t>(c.z()) * 83492791);
  }
  double cell_;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
};

bool share_face(const SurfaceMesh& m, int a, int b) {
  for (int h : m.outgoing_halfedges(a)) {
    const int f = m.face(h);
    if (f < 0) continue;
    const auto fv = m.face_vertices(f);
    if (std::find(fv.begin(), fv.end(), b) != fv.end()) return true;
  }
  return false;
}

std::string where(const Vec3& p) {
  std::ostringstream os;
  os << "[" << p.transpose() << "]";
  return os.str();
}

}  // namespace

CurveOnSurface project_curve(const SurfaceMesh& mesh, const MatrixX3& control, bool closed, double step,
                             double max_distance, const std::string& who) {
  const int n = static_cast<int>(control.rows());
  if (n < 2) throw InvalidInput(who + ": a curve needs at least 2 points");
  std::vector<Vec3> samples;
  CurveOnSurface c;
  c.closed = closed;
  const int segments = closed ? n : n - 1;
  for (int s = 0; s < segments; ++s) {
    const Vec3 a = control.row(s).transpose(), b = control.row((s + 1) % n).transpose();
    const int pieces = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
    for (int k = 0; k < pieces; ++k) {
      const double f = static_cast<double>(k) / pieces;
      samples.push_back((1 - f) * a + f * b);
      c.source.push_back(s + f);
    }
  }
  if (!closed) {
    samples.push_back(control.row(n - 1).transpose());
    c.source.push_back(n - 1);
  }
  MatrixX3 raw(static_cast<Eigen::Index>(samples.size()), 3);
  for (std::size_t i = 0; i < samples.size(); ++i) raw.row(static_cast<Eigen::Index>(i)) = samples[i].transpose();
  c.points = ClosestPointQuery(mesh).closest_points(raw);
  for (Eigen::Index i = 0; i < raw.rows(); ++i) {
    const double d = (raw.row(i) - c.points.row(i)).norm();
    if (!(d <= max_distance)) {
      std::ostringstream os;
      os << who << ": the curve leaves the surface near " << where(raw.row(i).transpose()) << " (between points "
         << static_cast<int>(c.source[static_cast<std::size_t>(i)]) << " and "
         << static_cast<int>(c.source[static_cast<std::size_t>(i)]) + 1 << "): it is " << d
         << " away, more than max_distance " << max_distance;
      throw InvalidInput(os.str());
    }
  }
  c.arc.assign(samples.size(), 0.0);
  for (std::size_t i = 1; i < samples.size(); ++i)
    c.arc[i] = c.arc[i - 1] +
               (c.points.row(static_cast<Eigen::Index>(i)) - c.points.row(static_cast<Eigen::Index>(i - 1))).norm();
  return c;
}

std::optional<SnappedChain> snap_vertices(const SurfaceMesh& m, const CurveOnSurface& c, double snap_ratio,
                                          std::string* why) {
  const MatrixX3& V = m.positions();
  const int nv = m.n_vertices();
  std::vector<double> radius(nv, 0.0), reach(nv, 0.0);  // snap radius; longest incident edge
  double max_radius = 0;
  for (int v = 0; v < nv; ++v) {
    if (m.is_isolated(v)) continue;
    double shortest = std::numeric_limits<double>::infinity();
    for (int nb : m.vertex_neighbors(v)) {
      const double len = (V.row(v) - V.row(nb)).norm();
      shortest = std::min(shortest, len);
      reach[v] = std::max(reach[v], len);
    }
    radius[v] = snap_ratio * shortest;
    max_radius = std::max(max_radius, radius[v]);
  }
  // For every vertex near the curve, its closest curve point (distance, arc length, sample).
  struct Hit { double distance, arc, source; Vec3 point; };
  std::unordered_map<int, Hit> hits;
  const VertexGrid grid(V, std::max(max_radius, 1e-300));
  const Eigen::Index samples = c.points.rows();
  const Eigen::Index segments = c.closed ? samples : samples - 1;
  for (Eigen::Index s = 0; s < segments; ++s) {
    const Eigen::Index s1 = (s + 1) % samples;
    const Vec3 a = c.points.row(s).transpose(), b = c.points.row(s1).transpose();
    const double len2 = (b - a).squaredNorm();
    const double arc1 = s1 == 0 ? c.arc.back() + (b - a).norm() : c.arc[static_cast<std::size_t>(s1)];
    const double src1 = s1 == 0 ? c.source.back() + 1.0 : c.source[static_cast<std::size_t>(s1)];
    const Vec3 pad = Vec3::Constant(max_radius);
    grid.near_box(a.cwiseMin(b) - pad, a.cwiseMax(b) + pad, [&](int v) {
      const Vec3 p = V.row(v).transpose();
      const double f = len2 > 0 ? std::clamp((p - a).dot(b - a) / len2, 0.0, 1.0) : 0.0;
      const Vec3 q = a + f * (b - a);
      const double d = (p - q).norm();
      if (d > radius[v]) return;
      auto [it, fresh] = hits.try_emplace(v, Hit{d, 0, 0, q});
      if (!fresh && it->second.distance <= d) return;
      const double arc0 = c.arc[static_cast<std::size_t>(s)], src0 = c.source[static_cast<std::size_t>(s)];
      it->second = {d, arc0 + f * (arc1 - arc0), src0 + f * (src1 - src0), q};
    });
  }
  std::vector<std::pair<double, int>> order;
  for (const auto& [v, hit] : hits) order.emplace_back(hit.arc, v);
  std::sort(order.begin(), order.end());
  if (order.empty()) {
    *why = "no vertex lies within snapping distance of the curve";
    return std::nullopt;
  }
  SnappedChain chain;
  for (const auto& [arc, v] : order) {
    chain.vertices.push_back(v);
    chain.on_curve.push_back(hits.at(v).point);
    chain.source.push_back(hits.at(v).source);
  }
  // (AP): no gaps along the curve, and the chain reaches both of its ends.
  const std::size_t k = chain.vertices.size();
  for (std::size_t i = 0; i + 1 < k + (c.closed ? 1 : 0); ++i) {
    const int a = chain.vertices[i], b = chain.vertices[(i + 1) % k];
    if (!share_face(m, a, b)) {
      *why = "gap between snapped vertices " + std::to_string(a) + " and " + std::to_string(b) + " near " +
             where(chain.on_curve[i]);
      return std::nullopt;
    }
  }
  if (!c.closed) {
    const Vec3 start = c.points.row(0).transpose(), end = c.points.row(samples - 1).transpose();
    if ((V.row(chain.vertices.front()).transpose() - start).norm() > reach[chain.vertices.front()] ||
        (V.row(chain.vertices.back()).transpose() - end).norm() > reach[chain.vertices.back()]) {
      *why = "the snapped vertices do not reach the curve's ends";
      return std::nullopt;
    }
  }
  return chain;
}

}  // namespace fairshape
