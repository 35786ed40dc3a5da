#include "fairshape/experiment/kinds/feature/feature_width_check.h"

namespace fairshape {

void check_feature_width(const FeatureSpec& f, const SurfaceMesh& base, int levels) {
  feature::check_feature_width(f, f.curve.params, base, levels);
  for (const FeatureChange& c : f.changes) feature::check_feature_width(f, c.params, base, levels);
}

}  // namespace fairshape
