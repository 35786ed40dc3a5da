// Constraints that ask two things of the same surface point. A weak (mortar) curve constraint
// ties only weighted means of w − D along its path, so another constraint *on* the path that asks
// a different position — a point, or another curve crossing or overlapping it — moves modes the
// means do not see: every row is met while the surface spikes and the curve's pointwise error is
// the difference of the two targets. In the continuous problem those are the only conflicts
// between position constraints (a point *beside* the path, however close, can be met with finite
// thin-plate energy: steep, but legal), so they are decided exactly here, from the targets at the
// shared parameter point, instead of from the discrete surface (papers/welch-witkin/README.md,
// "Curve constraints that conflict").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "fairshape/bspline/variational_sheet.h"

namespace fairshape::bspline {

struct Coincidence {
  int curve = -1;         // the curve constraint whose path holds the shared point
  int other = -1;         // the point or curve constraint there
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  double t = 0;           // the shared point on the curve's path (its parameter)
  double gap = 0;         // |what the curve asks − what the other asks| there (positions only)
};

//! Every parameter point a weak curve constraint shares with another constraint (uv within
//! `on_path`): points, tangents and normals on its path, curves crossing, touching or
//! overlapping it. `gap` compares positions (points, curves); tangents and normals have 0.
std::vector<Coincidence> coincidences(const std::vector<SheetConstraint>& constraints, double on_path);

//! The shared parameter points of a weak curve constraint and a point or curve constraint
//! (uv within `on_path` of each other) whose targets differ by more than `tolerance`: the
//! largest such gap, or nothing. Position targets only: tangents and normals on a path are not
//! compared (README: left open).
std::optional<Coincidence> conflicting_coincidence(const std::vector<SheetConstraint>& constraints, double on_path,
                                                   double tolerance);

//! The message of a conflict: both constraints, where (design units: (u, v) in spans times
//! span_size, SheetShape::span_size) and what each asks.
std::string describe(const Coincidence& c, const std::vector<SheetConstraint>& constraints, const Eigen::Vector2d& span_size);

}  // namespace fairshape::bspline
