// Reference back end of compute_perturbation: every vertex of the level against every segment of
// every curve, serially — the paper's description read literally.
#include "fairshape/feature/perturbation_backends.h"

namespace fairshape::feature {

LevelPerturbation perturbation_reference(const TriangleSurface& s, const std::vector<BaseCurve>& curves) {
  LevelPerturbation out;
  std::vector<Vec3> moved;
  for (int v = 0; v < s.mesh().n_vertices(); ++v) {
    OffsetCombiner combined;
    bool touched = false;
    for (const BaseCurve& curve : curves)
      for (int k = 0; k < static_cast<int>(curve.segments.size()); ++k)
        if (const auto o = segment_offset(s, curve, k, s.vertex(v))) {
          combined.add(*o);
          touched = true;
        }
    if (!touched) continue;
    out.vertices.push_back(v);
    moved.push_back(combined.displacement());
  }
  out.displacement.resize(static_cast<Eigen::Index>(moved.size()), 3);
  for (std::size_t i = 0; i < moved.size(); ++i) out.displacement.row(static_cast<Eigen::Index>(i)) = moved[i].transpose();
  return out;
}

LevelPerturbation perturb_vertices_reference(const TriangleSurface& s, const std::vector<BaseCurve>& curves,
                                             const std::vector<int>& vertices) {
  std::vector<Vec3> moved(vertices.size(), Vec3::Zero());
  std::vector<char> touched(vertices.size(), 0);
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    OffsetCombiner combined;
    for (const BaseCurve& curve : curves)
      for (int k = 0; k < static_cast<int>(curve.segments.size()); ++k)
        if (const auto o = segment_offset(s, curve, k, s.vertex(vertices[i]))) {
          combined.add(*o);
          touched[i] = 1;
        }
    moved[i] = combined.displacement();
  }
  return collect_moved(vertices, moved, touched);
}

LevelPerturbation displace_points_reference(const TriangleSurface& s, const std::vector<BaseCurve>& curves,
                                            const MatrixX3& points) {
  const auto n = static_cast<std::size_t>(points.rows());
  std::vector<int> ids(n);
  std::vector<Vec3> moved(n, Vec3::Zero());
  std::vector<char> touched(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    ids[i] = static_cast<int>(i);
    const Vec3 p = points.row(static_cast<Eigen::Index>(i)).transpose();
    OffsetCombiner combined;
    for (const BaseCurve& curve : curves)
      for (int k = 0; k < static_cast<int>(curve.segments.size()); ++k)
        if (const auto o = segment_offset(s, curve, k, p, OffsetMeaning::Displacement)) {
          combined.add(*o);
          touched[i] = 1;
        }
    moved[i] = combined.displacement();
  }
  return collect_moved(ids, moved, touched);
}

}  // namespace fairshape::feature
