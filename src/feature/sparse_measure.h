// What each feature achieves on a sparse Loop hierarchy (adaptive_evaluation.h): the
// measurement of profile_measure.h taken on the finest sparse level, at its control points and
// at the limit points of its vertices, so that a sparse run reports what a uniform run reports,
// whatever level a feature is drawn on (the requested profile composed as the uniform run
// composes it: sparse_visible_profile.h).
//
// The finest level is measured as a patch of its present faces (sparse_loop.h, make_patch); the
// vertices outside it have no displacement and change nothing. The limit point of a vertex is
// exact only where its whole one-ring is present ("complete"); the limit is measured on the
// vertices that are complete; the others keep their control point with no displacement (they change
// nothing). That needs every vertex the measure reads complete: those within the curve's reach,
// give or take twice the longest edge around them (a limit point lies in the hull of its
// one-ring; a moved control point moves its ring's limit points) — the feature's support refined
// completely. Where it is not, the limit is not measured and `limit_note` says why (a run
// reports it in its row as a miss, never a silent NaN). The local scale of each feature
// (feature_scale.h) is measured on what the run computed: the drawn level's patch around the
// curve and the base mesh, which is whole.
#pragma once

#include <string>
#include <vector>

#include "fairshape/feature/adaptive_evaluation.h"
#include "fairshape/feature/feature_scale.h"
#include "fairshape/feature/profile_measure.h"

namespace fairshape::feature {

struct SparseFeatureMeasure {
  ProfileMeasure fine, limit;
  bool limit_measured = false;
  std::string limit_note;  // why the limit is not measured ("" when it is)
  //! The local-scale check (feature_scale.h) on the computed region: the curvature on the drawn
  //! level's patch, the thickness against the patch and the whole base mesh, the base mesh's size.
  FeatureScale scale;
};

//! One entry per feature of `a` (input order), drawn on any level: measured against the targets
//! composed on the finest sparse level (sparse_visible_profile.h), as measure_features measures
//! a uniform evaluation. `opt` as the hierarchy was refined with (weights, boundary).
//! \throw std::logic_error when `a` lacks a level, its features' levels, a featured level's
//! positions before its features or the finest level's positions without features.
std::vector<SparseFeatureMeasure> measure_sparse_features(const AdaptiveEvaluation& a, int levels,
                                                          const SubdivisionOptions& opt, Backend backend);

}  // namespace fairshape::feature
