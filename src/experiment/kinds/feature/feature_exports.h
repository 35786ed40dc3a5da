// What a feature run exports beside final.obj: the result's limit surface, the
// per-level feature displacements the paper keeps apart from the surface (Khodakovsky &
// Schröder, §1.4: features live in the hierarchy as offsets of the level they are drawn on),
// and each curve's attachment (face, barycentric coordinates) on its drawn level and every
// finer one, carried to where the feature is.
#pragma once

#include <map>
#include <vector>

#include "fairshape/experiment/run_outputs.h"
#include "fairshape/feature/featured_surface.h"

namespace fairshape {

//! attachments.csv's columns: feature, level, point, face, b0, b1, b2, x, y, z (the point on that
//! level of the result, piecewise linearly).
const TableSchema& feature_attachment_table();

//! A curve's points on one level of the result: on its drawn level its own faces and coordinates,
//! on finer levels carried to where the feature is (feature/curve_on_level.h).
struct CurveOnLevel {
  int level = 0;
  std::vector<feature::SurfacePoint> at;
  std::vector<Vec3> x;
};

//! Every feature's curve on the finest level of the result, by id (for drawing it on the surface
//! it made).
std::map<int, std::vector<Vec3>> curves_on_finest_result(feature::FeaturedSurface& surface);

//! Adds a row per curve point and level to attachments.csv: the drawn level and every finer one.
void export_attachments(feature::FeaturedSurface& surface, const RunOutputs& out);

//! levels/<run>_level<k>.vtp for every level k: the result there, with point arrays
//! feature_displacement (the offsets the features put on that level's control points; 0 where
//! none) and displacement (result − surface without features); and limit/<run>.vtp: the finest
//! level's vertices moved to the limit surface, with limit_normal. Returns the finest level's
//! limit positions and normals for the caller's own VTP.
struct LimitSurface {
  MatrixX3 positions, normals;
};
LimitSurface export_levels_and_limit(feature::FeaturedSurface& surface, const RunOutputs& out);

}  // namespace fairshape
