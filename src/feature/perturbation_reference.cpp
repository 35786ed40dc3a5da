// Reference back end of compute_perturbation: every vertex of the level against every segment of
// every curve, serially — the paper's description read literally.
#include "feature/perturbation_backends.h"

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

}  // namespace fairshape::feature
