// A feature taller than its surface can hold turns faces over (a groove through the back of a
// thin part, a ridge whose flanks cross). Every feature run measures its finest result against
// the surface without features, as every surface run does, and a fold outranks a profile miss:
// the surface is wrong before its profile is (papers/khodakovsky-schroder/README.md, "Folds").
#pragma once

#include "fairshape/experiment/run_outputs.h"
#include "fairshape/mesh/orientation.h"

namespace fairshape {

//! runs.csv's flipped_faces; with a flip, termination `folded` and a message naming it (and the
//! profile miss the row already had, if any).
void report_folds(const FoldReport& folds, MetricRow& row);

}  // namespace fairshape
