// A feature run's design steps: between steps features are added, moved as a
// whole, re-parameterized or removed — the editing session of Khodakovsky & Schröder §2.6, where
// features are definitions re-applied to the surface, not baked into it. Each step is evaluated
// and reported in steps.csv with how much of the surface it changed.
#pragma once

#include "fairshape/experiment/kinds/feature/feature_run.h"

namespace fairshape {

//! steps.csv's columns: step, features, added, moved, changed, removed, vertices_changed (finest
//! vertices the step moved), evaluation (region: only what the step's features reach was
//! recomputed, FeaturedSurface::set_region_evaluation; whole), apply_s (its time),
//! vertices_recomputed (vertices of all levels recomputed), max_change.
const TableSchema& feature_step_table();

//! The number of design steps the features schedule (1 + the latest step, until, move or change).
int feature_step_count(const FeatureRunSpec& spec);

//! Evaluates step 0 (the features placed already) and every later step's additions, moves,
//! changes and removals, each a step of the session (FeatureSession::apply); writes steps.csv rows and, with output.vtk: all, vtk/<run>_step<k>.vtp.
//! Returns the last step's evaluation time. \throw InvalidInput naming a feature that cannot be
//! placed or applied.
double run_feature_steps(FeatureRunSpec& spec, FeatureSession& session, const RunOutputs& out);

}  // namespace fairshape
