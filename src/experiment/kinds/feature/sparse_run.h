// A feature run on the sparse Loop hierarchy alone (adaptive.evaluation: sparse):
// Khodakovsky & Schröder §2.5 compute the surface only where it is refined, so a feature on a
// large model costs time and memory in proportion to its region, whatever level it is drawn on
// and wherever its profile is exact (profile_on: the region a coarse feature changes is computed
// down to the finest level, adaptive_evaluation.h). The uniform hierarchy is never built: the
// curves are placed on sparse levels (the placement tools on their whole level, computed when it
// has at most adaptive.placement_max_faces faces), final.obj is the adaptive mesh, features.csv
// is measured on the finest sparse level, attachments.csv comes from the sparse levels. What
// needs the whole surface (the VTK exports' limit surface and uniform levels, design steps
// re-evaluating the whole hierarchy, a placement tool on a larger level) is refused at load
// (FeatureRunSpec::from_config, or the validation's evaluation), naming the key.
#pragma once

#include "fairshape/experiment/kinds/feature/feature_run.h"

namespace fairshape {

//! Checks the config keys a sparse run cannot honour. \throw InvalidConfig naming the key and
//! the valid choices.
void check_sparse_run(const FeatureRunSpec& spec);

//! Validation of a sparse run before the sweep starts: the features placed and evaluated on the
//! sparse levels (cheap: the refined region), never the uniform hierarchy. \throw Error for the
//! input, as the run would.
void check_sparse_features(FeatureRunSpec& spec);

//! Fills `row` (runs.csv) and writes final.obj, adaptive/<run>.obj, curves/, features.csv and
//! attachments.csv. \throw Error for the input (a feature that cannot be placed or applied).
void execute_sparse_feature_run(FeatureRunSpec& spec, const RunOutputs& out, MetricRow& row);

}  // namespace fairshape
