// Optimized back end of compute_perturbation. The segments go into a uniform grid whose cells
// are as wide as the largest reach (feature size plus the longest edge): each segment is listed
// in every cell its reach-widened bounding box overlaps, so a vertex's own cell lists every
// segment that can move it. The moved region is gathered by a walk over the vertex graph from
// the segments' faces through vertices within reach of a listed segment (reach includes the
// longest edge, so the walk cannot be cut off by a vertex just outside), and its vertices are
// evaluated in parallel against their cell's list — in curve and segment order, as the
// reference does, so the two agree exactly.
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <unordered_map>

#include "fairshape/feature/perturbation_backends.h"

namespace fairshape::feature {
namespace {

struct SegmentRef {
  int curve, segment;
  double reach;
};

class SegmentGrid {
 public:
  SegmentGrid(const std::vector<BaseCurve>& curves, double longest_edge) {
    for (const BaseCurve& c : curves) cell_ = std::max(cell_, std::max(c.params.radius, c.params.right_radius()) + longest_edge);
    for (int c = 0; c < static_cast<int>(curves.size()); ++c) {
      const double reach = std::max(curves[c].params.radius, curves[c].params.right_radius()) + longest_edge;
      for (int k = 0; k < static_cast<int>(curves[c].segments.size()); ++k) {
        const BaseSegment& seg = curves[c].segments[static_cast<std::size_t>(k)];
        const Eigen::Vector3i lo = cell_of(seg.a.cwiseMin(seg.b).array() - reach), hi = cell_of(seg.a.cwiseMax(seg.b).array() + reach);
        for (int x = lo.x(); x <= hi.x(); ++x)
          for (int y = lo.y(); y <= hi.y(); ++y)
            for (int z = lo.z(); z <= hi.z(); ++z) cells_[key(x, y, z)].push_back({c, k, reach});
      }
    }
  }
  //! Segments that may reach p, in curve and segment order (empty if none).
  const std::vector<SegmentRef>& near(const Vec3& p) const {
    if (cells_.empty() || !p.allFinite()) return empty_;  // no segment (every feature removed): cell_ is 0
    const Eigen::Vector3i c = cell_of(p);
    const auto it = cells_.find(key(c.x(), c.y(), c.z()));
    return it == cells_.end() ? empty_ : it->second;
  }

 private:
  // Clamped before the cast, which is undefined beyond int's range (the key keeps 21 bits anyway).
  Eigen::Vector3i cell_of(const Vec3& p) const {
    constexpr double kLimit = 1 << 20;
    return (p / cell_).array().floor().max(-kLimit).min(kLimit).cast<int>().matrix();
  }
  static std::uint64_t key(int x, int y, int z) {
    const auto u = [](int v) { return static_cast<std::uint64_t>(static_cast<std::uint32_t>(v) & 0x1fffff); };
    return u(x) | (u(y) << 21) | (u(z) << 42);
  }
  double cell_ = 0;
  std::unordered_map<std::uint64_t, std::vector<SegmentRef>> cells_;
  std::vector<SegmentRef> empty_;
};

// The offsets of the listed vertices (in parallel), each against its grid cell's segments.
LevelPerturbation perturb_listed(const TriangleSurface& s, const std::vector<BaseCurve>& curves, const SegmentGrid& grid,
                                 const std::vector<int>& vertices) {
  const std::size_t n = vertices.size();
  std::vector<Vec3> moved(n);
  std::vector<char> touched(n, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 64), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const Vec3 p = s.vertex(vertices[i]);
      OffsetCombiner combined;
      for (const SegmentRef& ref : grid.near(p)) {
        const BaseCurve& curve = curves[static_cast<std::size_t>(ref.curve)];
        // segment_offset's own first test, inlined: most listed segments are out of reach.
        const double reach = std::max(curve.params.radius, curve.params.right_radius());
        if (curve.segments[static_cast<std::size_t>(ref.segment)].squared_distance(p) >= reach * reach) continue;
        if (const auto o = segment_offset(s, curve, ref.segment, p)) {
          combined.add(*o);
          touched[i] = 1;
        }
      }
      moved[i] = combined.displacement();
    }
  });
  return collect_moved(vertices, moved, touched);
}

}  // namespace

LevelPerturbation perturbation_tbb(const TriangleSurface& s, const std::vector<BaseCurve>& curves) {
  const SurfaceMesh& m = s.mesh();
  const SegmentGrid grid(curves, s.longest_edge());
  const auto reaches = [&](const SegmentRef& r, const Vec3& p) {
    return curves[static_cast<std::size_t>(r.curve)].segments[static_cast<std::size_t>(r.segment)].squared_distance(p) <
           r.reach * r.reach;
  };
  // The segment that last had a vertex in reach is tried first (per task: the walk moves between
  // neighbours, so it usually still reaches).
  const auto within_reach = [&](const Vec3& p, const SegmentRef*& hint) {
    if (hint && reaches(*hint, p)) return true;
    for (const SegmentRef& r : grid.near(p))
      if (reaches(r, p)) {
        hint = &r;
        return true;
      }
    return false;
  };
  // The region: a breadth-first walk, frontier by frontier, each frontier in parallel. A vertex
  // is claimed (and tested) once through an atomic state, so the region does not depend on the
  // thread count (it is sorted afterwards).
  enum : char { kUntested, kClaimed };
  std::vector<std::atomic<char>> state(static_cast<std::size_t>(m.n_vertices()));
  std::vector<int> region, frontier;
  for (const BaseCurve& c : curves)
    for (const BaseSegment& seg : c.segments)
      for (int v : s.corners(seg.face))
        if (state[static_cast<std::size_t>(v)].exchange(kClaimed) == kUntested) frontier.push_back(v);
  tbb::enumerable_thread_specific<std::vector<int>> next_parts;
  while (!frontier.empty()) {
    region.insert(region.end(), frontier.begin(), frontier.end());
    for (auto& part : next_parts) part.clear();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, frontier.size(), 256), [&](const tbb::blocked_range<std::size_t>& r) {
      std::vector<int>& next = next_parts.local();
      const SegmentRef* hint = nullptr;
      for (std::size_t i = r.begin(); i != r.end(); ++i)
        m.for_each_outgoing(frontier[i], [&](int h) {
          const int w = m.to_vertex(h);
          std::atomic<char>& st = state[static_cast<std::size_t>(w)];
          if (st.load(std::memory_order_relaxed) != kUntested || st.exchange(kClaimed) != kUntested) return;
          if (within_reach(s.vertex(w), hint)) next.push_back(w);
        });
    });
    frontier.clear();
    for (const auto& part : next_parts) frontier.insert(frontier.end(), part.begin(), part.end());
  }
  std::sort(region.begin(), region.end());
  return perturb_listed(s, curves, grid, region);
}

LevelPerturbation perturb_vertices_tbb(const TriangleSurface& s, const std::vector<BaseCurve>& curves,
                                       const std::vector<int>& vertices) {
  return perturb_listed(s, curves, SegmentGrid(curves, s.longest_edge()), vertices);
}

// Points are not vertices of the level: no region walk, each point looks up its grid cell (the
// cells list the segments in curve and segment order, as the reference scans them).
LevelPerturbation displace_points_tbb(const TriangleSurface& s, const std::vector<BaseCurve>& curves,
                                      const MatrixX3& points) {
  const SegmentGrid grid(curves, s.longest_edge());
  const auto n = static_cast<std::size_t>(points.rows());
  std::vector<int> ids(n);
  std::vector<Vec3> moved(n, Vec3::Zero());
  std::vector<char> touched(n, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      ids[i] = static_cast<int>(i);
      const Vec3 p = points.row(static_cast<Eigen::Index>(i)).transpose();
      OffsetCombiner combined;
      for (const SegmentRef& ref : grid.near(p)) {
        const BaseCurve& curve = curves[static_cast<std::size_t>(ref.curve)];
        const double reach = std::max(curve.params.radius, curve.params.right_radius());
        if (curve.segments[static_cast<std::size_t>(ref.segment)].squared_distance(p) >= reach * reach) continue;
        if (const auto o = segment_offset(s, curve, ref.segment, p, OffsetMeaning::Displacement)) {
          combined.add(*o);
          touched[i] = 1;
        }
      }
      moved[i] = combined.displacement();
    }
  });
  return collect_moved(ids, moved, touched);
}

}  // namespace fairshape::feature
