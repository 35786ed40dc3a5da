// The two back ends of compute_perturbation (perturbation.h) and what they share.
#pragma once

#include "fairshape/feature/perturbation.h"

namespace fairshape::feature {

//! Raises and cuts of one control point, combined as §2.3 describes (perturbation.cpp).
struct OffsetCombiner {
  SegmentOffset raise, cut;
  void add(const SegmentOffset& o);
  Vec3 displacement() const;
};

LevelPerturbation perturbation_reference(const TriangleSurface& s, const std::vector<BaseCurve>& curves);
LevelPerturbation perturbation_tbb(const TriangleSurface& s, const std::vector<BaseCurve>& curves);
LevelPerturbation displace_points_reference(const TriangleSurface& s, const std::vector<BaseCurve>& curves,
                                            const MatrixX3& points);
LevelPerturbation displace_points_tbb(const TriangleSurface& s, const std::vector<BaseCurve>& curves,
                                      const MatrixX3& points);
LevelPerturbation perturb_vertices_reference(const TriangleSurface& s, const std::vector<BaseCurve>& curves,
                                             const std::vector<int>& vertices);
LevelPerturbation perturb_vertices_tbb(const TriangleSurface& s, const std::vector<BaseCurve>& curves,
                                       const std::vector<int>& vertices);
//! The rows of `moved` whose `touched` flag is set, as a LevelPerturbation.
LevelPerturbation collect_moved(const std::vector<int>& ids, const std::vector<Vec3>& moved, const std::vector<char>& touched);

}  // namespace fairshape::feature
