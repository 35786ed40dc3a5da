// The two back ends of compute_perturbation (perturbation.h) and what they share.
#pragma once

#include "feature/perturbation.h"

namespace fairshape::feature {

//! Raises and cuts of one control point, combined as §2.3 describes (perturbation.cpp).
struct OffsetCombiner {
  SegmentOffset raise, cut;
  void add(const SegmentOffset& o);
  Vec3 displacement() const;
};

LevelPerturbation perturbation_reference(const TriangleSurface& s, const std::vector<BaseCurve>& curves);
LevelPerturbation perturbation_tbb(const TriangleSurface& s, const std::vector<BaseCurve>& curves);

}  // namespace fairshape::feature
