// Optimized back end of compute_perturbation: each segment's neighbourhood is gathered by a walk
// over the vertex graph from the segment's face (vertices closer than the feature's size plus
// the longest edge, so the walk cannot be cut off by a vertex just outside), the candidate
// (vertex, segment) pairs are sorted into the reference's order, and the vertices are
// evaluated in parallel.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "feature/perturbation_backends.h"

namespace fairshape::feature {
namespace {

double distance_to_segment(const BaseSegment& seg, const Vec3& p) {
  const Vec3 ab = seg.b - seg.a;
  const double t = std::clamp((p - seg.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (seg.a + t * ab)).norm();
}

struct Candidate {
  int vertex, curve, segment;
  bool operator<(const Candidate& o) const {
    return std::tie(vertex, curve, segment) < std::tie(o.vertex, o.curve, o.segment);
  }
};

}  // namespace

LevelPerturbation perturbation_tbb(const TriangleSurface& s, const std::vector<BaseCurve>& curves) {
  const SurfaceMesh& m = s.mesh();
  const double h = s.longest_edge();
  std::vector<Candidate> candidates;
  std::vector<int> seen(static_cast<std::size_t>(m.n_vertices()), -1);  // stamp: last segment that saw it
  int stamp = 0;
  std::vector<int> queue;
  for (int c = 0; c < static_cast<int>(curves.size()); ++c) {
    const double reach = std::max(curves[c].params.radius, curves[c].params.right_radius()) + h;
    for (int k = 0; k < static_cast<int>(curves[c].segments.size()); ++k, ++stamp) {
      const BaseSegment& seg = curves[c].segments[static_cast<std::size_t>(k)];
      queue.assign(s.corners(seg.face).begin(), s.corners(seg.face).end());
      for (int v : queue) seen[static_cast<std::size_t>(v)] = stamp;
      for (std::size_t head = 0; head < queue.size(); ++head) {
        const int v = queue[head];
        candidates.push_back({v, c, k});
        for (int w : m.vertex_neighbors(v))
          if (seen[static_cast<std::size_t>(w)] != stamp && distance_to_segment(seg, s.vertex(w)) < reach) {
            seen[static_cast<std::size_t>(w)] = stamp;
            queue.push_back(w);
          }
      }
    }
  }
  std::sort(candidates.begin(), candidates.end());
  std::vector<std::size_t> starts;  // first candidate of each distinct vertex
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (i == 0 || candidates[i].vertex != candidates[i - 1].vertex) starts.push_back(i);
  starts.push_back(candidates.size());
  const std::size_t n = starts.size() - 1;
  std::vector<Vec3> moved(n);
  std::vector<char> touched(n, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 64), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      OffsetCombiner combined;
      for (std::size_t j = starts[i]; j < starts[i + 1]; ++j) {
        const Candidate& cand = candidates[j];
        if (const auto o = segment_offset(s, curves[static_cast<std::size_t>(cand.curve)], cand.segment,
                                          s.vertex(cand.vertex))) {
          combined.add(*o);
          touched[i] = 1;
        }
      }
      moved[i] = combined.displacement();
    }
  });
  LevelPerturbation out;
  for (std::size_t i = 0; i < n; ++i)
    if (touched[i]) out.vertices.push_back(candidates[starts[i]].vertex);
  out.displacement.resize(static_cast<Eigen::Index>(out.vertices.size()), 3);
  for (std::size_t i = 0, row = 0; i < n; ++i)
    if (touched[i]) out.displacement.row(static_cast<Eigen::Index>(row++)) = moved[i].transpose();
  return out;
}

LevelPerturbation compute_perturbation(const TriangleSurface& s, const std::vector<BaseCurve>& curves,
                                       Backend backend) {
  return backend == Backend::Reference ? perturbation_reference(s, curves) : perturbation_tbb(s, curves);
}

}  // namespace fairshape::feature
