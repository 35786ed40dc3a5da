// The profile where it is seen (visible_profile.h) on a sparse Loop hierarchy
// (sparse_loop.h): Khodakovsky & Schröder ("Fine level feature editing for subdivision
// surfaces", §2.5) compute the surface only where it is refined, and a feature drawn on level
// l < L is seen on the finest level L and at the limit. The uniform evaluation
// (FeaturedSurface) composes the features' displacements on the whole finest level without
// features; here the same composition runs on the finest sparse level's present faces as a
// patch (its positions without features, SparseLevel::original), with each level's operator on
// the patch of that level before its features. A vertex's displacement reads only its own
// point and the operator's level, so every present vertex gets the uniform value; the limit
// point of a vertex is exact only where its whole one-ring is present ("complete"): the others
// keep their control point in every limit target (they must lie outside every feature's reach,
// which the adaptive evaluation ensures, adaptive_evaluation.h).
#pragma once

#include <vector>

#include "fairshape/feature/sparse_loop.h"
#include "fairshape/feature/visible_profile.h"

namespace fairshape::feature {

struct SparseVisibleTargets {
  SparsePatch finest;             // the finest level's present faces, positions without features
  std::vector<char> complete;     // per patch vertex: its whole uniform one-ring is present
  std::vector<LevelOperator> operators;  // coarse to fine; ids: the features' input indices
  VisibleTargets targets;         // as compose_visible_targets, rows by patch vertex
};

//! `levels` 0..L with SparseLevel::original on L, `unperturbed[l]` each featured level's
//! positions before its features, `curves` and `curve_level` per feature (input order; the
//! segments' faces local to levels[level]). \throw std::logic_error when a featured level lacks
//! its positions before the features or L lacks its original positions.
SparseVisibleTargets sparse_visible_targets(const std::vector<SparseLevel>& levels, const std::vector<MatrixX3>& unperturbed,
                                            const std::vector<BaseCurve>& curves, const std::vector<int>& curve_level,
                                            const SubdivisionOptions& opt, Backend backend);

}  // namespace fairshape::feature
