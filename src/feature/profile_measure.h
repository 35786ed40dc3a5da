// What a feature achieves where it is seen: per feature, on the finest level's control
// points and on the limit points of the finest vertices, the height at the curve, the width on
// each side and the deviation from the requested cross-section. Definitions (all relative to the
// surface the feature was applied to — the original, or the coarser features' visible target):
//   height      the displacement along the curve's normal at samples of the base curve (about
//               one per finest edge: the longest edge of the segment's face on the drawn level,
//               halved per finer level), interpolated linearly in the finest face below the sample;
//               samples within another feature's reach are skipped (its height is theirs too);
//   profile     max over the finest vertices within the feature's reach plus its curve's edge
//               (measured_reach: outside every other feature's reach) of |achieved − requested position|; requested = the profile as
//               a displacement (perturbation.h, OffsetMeaning::Displacement) of that surface;
//   width       r × (displacement-weighted mean distance from the curve, achieved / requested),
//               per side: the radius whose profile of the requested shape would spread its
//               displacement as far as the achieved one does (a wider, flatter groove reads > r);
// height and profile errors are fractions of |height| (the larger of start and end height),
// widths of the radius on that side.
#pragma once

#include <string>
#include <vector>

#include "fairshape/feature/featured_surface.h"

namespace fairshape::feature {

struct ProfileMeasure {
  double height_min = 0, height_max = 0;  // achieved, world units (NaN: every sample shared)
  double height_error = 0;                // max |achieved − requested| at the curve / |h|
  double width_left = 0, width_right = 0;  // world units (NaN: no displacement on that side)
  double width_error = 0;                 // max over sides |width − r_side| / r_side
  double profile_error = 0;               // max |achieved − requested| / |h| over its vertices
};

struct FeatureMeasure {
  int id = -1;
  std::string name;
  int level = 0;
  ProfileMeasure fine, limit;
  bool within_tolerance = true;
  std::string why;  // the first miss: "limit: profile error 0.063 > profile_tolerance 0.02"
};

//! How far from `curve` the measure reads finest vertices: its reach plus the longest edge of
//! the faces it crosses on `level` (the level it is drawn on) — the drawn-level profile's
//! smoothing spills over the reach by about that much. Local to the curve, so that a sparse run,
//! which holds only the curve's region of the level, reads the same vertices a uniform run does.
double measured_reach(const TriangleSurface& level, const BaseCurve& curve);

//! The finest-level measure of one curve on any mesh that holds the curve's support (a sparse
//! run's finest level as a patch, feature/sparse_loop.h: the vertices outside it have no
//! displacement and change nothing): positions per vertex of `mesh` of the surface the curve
//! was applied to, of what was asked and of what was achieved; `level` the surface the curve
//! was built on (`levels_to_finest` levels coarser than `mesh`), `others` the run's other curves.
ProfileMeasure measure_on_mesh(const SurfaceMesh& mesh, const MatrixX3& reference, const MatrixX3& requested,
                               const MatrixX3& achieved, const TriangleSurface& level, const BaseCurve& curve,
                               const std::vector<const BaseCurve*>& others, int levels_to_finest = 0);
//! The first tolerance `m` misses ("<where>: profile error … > profile_tolerance …"), or "".
std::string profile_miss(const char* where, const ProfileMeasure& m, const FeatureParams& q);

//! Which measured surface decides a feature's verdict (README, "What level l means"): the one
//! `profile_on` makes exact — `limit` the limit points, `finest` the finest control points. The
//! other one differs from it by the Loop smoothing of the displacement, about h (h_L / r)²: it
//! is reported (features.csv's columns) but does not decide. `drawn_level` makes neither exact
//! (the paper's own surface, the drawn level's control points, is not what is seen), so both
//! visible surfaces decide, as they did.
struct ProfileGates {
  bool fine = true, limit = true;
};
ProfileGates profile_gates(ProfileTarget target);
//! features.csv's `gated_on`: "limit", "finest" or "finest+limit".
const char* gates_name(ProfileGates g);

//! One entry per feature, in id order, its verdict taken on the surface(s) profile_gates names for
//! the surface's ProfileTarget and on the local scale (feature_scale.h). Evaluates the surface.
std::vector<FeatureMeasure> measure_features(FeaturedSurface& surface);

}  // namespace fairshape::feature
