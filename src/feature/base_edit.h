// A coarse edit of the base surface under its features (Khodakovsky & Schröder Figure 15):
// the features, stored as details above it, follow the edited base.
#pragma once

#include "fairshape/mesh/surface_mesh.h"

namespace fairshape::feature {

struct BaseEdit {
  Vec3 nearest = Vec3::Zero();  // the edit's centre: the base vertex nearest to this point
  Vec3 offset = Vec3::Zero();   // displacement of the centre
  double radius = 0.3;          // falloff radius × the bounding-box diagonal `diag`
};

//! The base positions with a smooth (C²) bump (1 − t²)³ · offset, t = distance / (radius · diag).
MatrixX3 bumped_positions(const SurfaceMesh& base, const BaseEdit& e, double diag);

}  // namespace fairshape::feature
