// Subdivision schemes, boundary modes and weight choices, with their names as written in
// configs and on the command line.
#pragma once

#include <string>
#include <string_view>

#include "core/name_table.h"

namespace fairshape {

enum class SchemeType { CatmullClark, Loop };

// As in OpenSubdiv: boundary curves follow the cubic B-spline rules in both modes;
// EdgeAndCorner also pins every boundary vertex that belongs to exactly one face.
enum class BoundaryMode { EdgeOnly, EdgeAndCorner };

// Loop's vertex weight β(k): Loop's original (the default, as in OpenSubdiv) or Warren's
// simplification used by Khodakovsky & Schröder.
enum class LoopWeights { Loop, Warren };

struct SubdivisionOptions {
  SchemeType scheme = SchemeType::CatmullClark;
  BoundaryMode boundary = BoundaryMode::EdgeOnly;
  LoopWeights weights = LoopWeights::Loop;
};

const NameTable<SchemeType>& scheme_names();
const NameTable<BoundaryMode>& boundary_names();
const NameTable<LoopWeights>& loop_weight_names();
std::string_view to_string(SchemeType s);
std::string_view to_string(BoundaryMode b);
std::string_view to_string(LoopWeights w);
SchemeType scheme_from_string(std::string_view s);        // "catmull-clark" | "loop"
BoundaryMode boundary_from_string(std::string_view s);    // "edge-only" | "edge-and-corner"
LoopWeights loop_weights_from_string(std::string_view s);  // "loop" | "warren"

//! β of an interior vertex of valence k (the weight of each neighbour in the even rule).
double loop_beta(int valence, LoopWeights weights);

}  // namespace fairshape
