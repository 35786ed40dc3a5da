#include "fairshape/subdivision/scheme.h"

#include <cmath>

#include "fairshape/core/error.h"

namespace fairshape {

const NameTable<SchemeType>& scheme_names() {
  static const NameTable<SchemeType> t{{SchemeType::CatmullClark, "catmull-clark"}, {SchemeType::Loop, "loop"}};
  return t;
}
const NameTable<BoundaryMode>& boundary_names() {
  static const NameTable<BoundaryMode> t{{BoundaryMode::EdgeOnly, "edge-only"},
                                         {BoundaryMode::EdgeAndCorner, "edge-and-corner"}};
  return t;
}
const NameTable<LoopWeights>& loop_weight_names() {
  static const NameTable<LoopWeights> t{{LoopWeights::Loop, "loop"}, {LoopWeights::Warren, "warren"}};
  return t;
}
const NameTable<CreaseMethod>& crease_method_names() {
  static const NameTable<CreaseMethod> t{{CreaseMethod::Uniform, "uniform"}, {CreaseMethod::Chaikin, "chaikin"}};
  return t;
}

std::string_view to_string(SchemeType s) { return scheme_names().name(s); }
std::string_view to_string(BoundaryMode b) { return boundary_names().name(b); }
std::string_view to_string(LoopWeights w) { return loop_weight_names().name(w); }
std::string_view to_string(CreaseMethod c) { return crease_method_names().name(c); }
SchemeType scheme_from_string(std::string_view s) { return scheme_names().value(s, "subdivision scheme"); }
BoundaryMode boundary_from_string(std::string_view s) { return boundary_names().value(s, "boundary mode"); }
LoopWeights loop_weights_from_string(std::string_view s) { return loop_weight_names().value(s, "Loop weights"); }
CreaseMethod crease_method_from_string(std::string_view s) { return crease_method_names().value(s, "crease method"); }

double loop_beta(int k, LoopWeights weights) {
  if (weights == LoopWeights::Warren) return k == 3 ? 3.0 / 16.0 : 3.0 / (8.0 * k);
  const double c = 3.0 / 8.0 + 0.25 * std::cos(2.0 * M_PI / k);
  return (5.0 / 8.0 - c * c) / k;
}

}  // namespace fairshape
