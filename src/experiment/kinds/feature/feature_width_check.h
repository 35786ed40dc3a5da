// A feature narrower than about two edges of the finest level is refused at load. Its cubic
// profile (Khodakovsky & Schröder §2.1.3) falls from the crest to zero within the radius; the
// finest control points and the limit points of the finest vertices are one sample per edge,
// so across fewer than two edges per side neither can show that profile and the measurement
// (profile_measure.h: heights about one per finest edge) cannot vouch for it — the run would only
// find the miss afterwards, or pass on too few samples to mean anything
// (papers/khodakovsky-schroder/README.md, "Features narrower than the finest level").
#pragma once

#include "fairshape/experiment/kinds/feature/feature_run.h"
#include "fairshape/feature/feature_drawing.h"

namespace fairshape {

//! feature::check_feature_width for the feature's parameters and every later `changes` entry's.
//! \throw InvalidConfig naming `f.key`.radius. \pre f.curve.points placed.
void check_feature_width(const FeatureSpec& f, const SurfaceMesh& base, int levels);

}  // namespace fairshape
