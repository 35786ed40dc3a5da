// A feature narrower than about two edges of the finest level is refused at load. Its cubic
// profile (Khodakovsky & Schröder §2.1.3) falls from the crest to zero within the radius; the
// finest control points and the limit points of the finest vertices are one sample per edge,
// so across fewer than two edges per side neither can show that profile and the measurement
// (profile_measure.h: heights about one per finest edge) cannot vouch for it — the run would only
// find the miss afterwards, or pass on too few samples to mean anything
// (papers/khodakovsky-schroder/README.md, "Features narrower than the finest level").
#pragma once

#include "fairshape/experiment/kinds/feature/feature_run.h"

namespace fairshape {

//! The typical finest edge under a placed curve: per control point, the mean edge of the base
//! face it lies in (uniform face ids: the base ancestor of face f on level l is f / 4^l), halved
//! for each of `levels` Loop steps; the mean over the points. The same in uniform and sparse runs
//! (both have the base mesh whole).
double finest_edge_under(const feature::FeatureCurve& curve, const SurfaceMesh& base, int levels);

//! \throw InvalidConfig naming `f.key`.radius, the smaller radius (with its `changes` too), the
//! finest edge and what to change (more levels or a wider radius) when a side of `f` is narrower
//! than two finest edges. \pre f.curve.points placed (uniform face ids of f.curve.level).
void check_feature_width(const FeatureSpec& f, const SurfaceMesh& base, int levels);

}  // namespace fairshape
