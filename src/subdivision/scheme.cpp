#include "subdivision/scheme.h"

#include <cmath>

#include "core/error.h"

namespace fairshape {

std::string_view to_string(SchemeType s) { return s == SchemeType::CatmullClark ? "catmull-clark" : "loop"; }
std::string_view to_string(BoundaryMode b) { return b == BoundaryMode::EdgeOnly ? "edge-only" : "edge-and-corner"; }
std::string_view to_string(LoopWeights w) { return w == LoopWeights::Loop ? "loop" : "warren"; }

SchemeType scheme_from_string(std::string_view s) {
  if (s == "catmull-clark") return SchemeType::CatmullClark;
  if (s == "loop") return SchemeType::Loop;
  throw InvalidConfig("unknown subdivision scheme '" + std::string(s) + "' (valid: catmull-clark, loop)");
}

BoundaryMode boundary_from_string(std::string_view s) {
  if (s == "edge-only") return BoundaryMode::EdgeOnly;
  if (s == "edge-and-corner") return BoundaryMode::EdgeAndCorner;
  throw InvalidConfig("unknown boundary mode '" + std::string(s) + "' (valid: edge-only, edge-and-corner)");
}

LoopWeights loop_weights_from_string(std::string_view s) {
  if (s == "loop") return LoopWeights::Loop;
  if (s == "warren") return LoopWeights::Warren;
  throw InvalidConfig("unknown Loop weights '" + std::string(s) + "' (valid: loop, warren)");
}

double loop_beta(int k, LoopWeights weights) {
  if (weights == LoopWeights::Warren) return k == 3 ? 3.0 / 16.0 : 3.0 / (8.0 * k);
  const double c = 3.0 / 8.0 + 0.25 * std::cos(2.0 * M_PI / k);
  return (5.0 / 8.0 - c * c) / k;
}

}  // namespace fairshape
