// Subdivision schemes, boundary modes and weight choices, with their names as written in
// configs and on the command line.
#pragma once

#include <string>
#include <string_view>

#include "fairshape/core/name_table.h"

namespace fairshape {

enum class SchemeType { CatmullClark, Loop };

// As in OpenSubdiv: boundary curves follow the cubic B-spline rules in both modes;
// EdgeAndCorner also pins every boundary vertex that belongs to exactly one face.
enum class BoundaryMode { EdgeOnly, EdgeAndCorner };

// Loop's vertex weight β(k): Loop's original (the default, as in OpenSubdiv) or Warren's
// simplification used by Khodakovsky & Schröder.
enum class LoopWeights { Loop, Warren };

// How a semi-sharp crease's sharpness decays from one level to the next (OpenSubdiv's
// Sdc::Options::CreasingMethod): Uniform lowers every sharpness by one (OpenSubdiv's default);
// Chaikin first averages each semi-sharp edge with the other semi-sharp edges at the vertex
// its child half touches (3/4 own + 1/4 theirs), so a crease whose sharpness varies along it
// decays smoothly instead of in steps (crease_rules.h).
enum class CreaseMethod { Uniform, Chaikin };

struct SubdivisionOptions {
  SchemeType scheme = SchemeType::CatmullClark;
  BoundaryMode boundary = BoundaryMode::EdgeOnly;
  LoopWeights weights = LoopWeights::Loop;
  CreaseMethod crease = CreaseMethod::Uniform;
};

const NameTable<SchemeType>& scheme_names();
const NameTable<BoundaryMode>& boundary_names();
const NameTable<LoopWeights>& loop_weight_names();
const NameTable<CreaseMethod>& crease_method_names();
std::string_view to_string(SchemeType s);
std::string_view to_string(BoundaryMode b);
std::string_view to_string(LoopWeights w);
std::string_view to_string(CreaseMethod c);
SchemeType scheme_from_string(std::string_view s);        // "catmull-clark" | "loop"
BoundaryMode boundary_from_string(std::string_view s);    // "edge-only" | "edge-and-corner"
LoopWeights loop_weights_from_string(std::string_view s);  // "loop" | "warren"
CreaseMethod crease_method_from_string(std::string_view s);  // "uniform" | "chaikin"

//! β of an interior vertex of valence k (the weight of each neighbour in the even rule).
double loop_beta(int valence, LoopWeights weights);

}  // namespace fairshape
