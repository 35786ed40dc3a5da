// The perturbation of one level's control points by the feature curves drawn on it
// (Khodakovsky & Schröder, "Fine level feature editing for subdivision surfaces", §2.1–2.4).
// For a control point p and a base segment: the closest point b on the segment (skipped when b
// is an end point that the neighbouring segment does not also find closest, Figure 12), the frame
// at b (interpolated limit normal, the direction to p in the tangent plane), the ray from b
// towards p unrolled on the surface over the neighbourhood size r to the boundary point q, and a
// cubic profile over the unrolled length with value `height` and slope `crease` at b and the
// surface's height and slope at q. p moves along b's normal onto the profile. Offsets of several
// segments combine by a running maximum of the raises and minimum of the cuts, which are then
// added.
#pragma once

#include <optional>
#include <vector>

#include "fairshape/core/backend.h"
#include "fairshape/feature/feature_curve.h"

namespace fairshape::feature {

//! Displacements of the control points one level's features move (sorted vertex ids).
struct LevelPerturbation {
  std::vector<int> vertices;
  MatrixX3 displacement;
  MatrixX3 dense(int n_vertices) const;
};

//! The cubic with value h0 and slope m0 at 0, value h1 and slope m1 at `length`, at s.
double cubic_profile(double s, double length, double h0, double m0, double h1, double m1);

//! One segment's offset of p (none when p is outside the segment's region of influence).
struct SegmentOffset {
  double delta = 0;        // along the normal at the base point
  Vec3 normal = Vec3::Zero();
};
//! OntoProfile (the paper's, for the level's own control points): p moves onto the profile.
//! Displacement (for points of a finer level or of the limit surface near the level): p moves
//! along the base normal by the cubic with value `height` and slope `crease` at the curve and
//! value and slope 0 at the unrolled length — the paper's cubic less the cubic through the
//! section's own boundary values. On a plane both are the same; elsewhere this one leaves the
//! visible surface's own smooth shape under the feature instead of the level's flat facets
//! (whose kinks a finer surface would show) and joins it C¹ at the boundary.
enum class OffsetMeaning { OntoProfile, Displacement };
std::optional<SegmentOffset> segment_offset(const TriangleSurface& s, const BaseCurve& curve, int segment,
                                            const Vec3& p, OffsetMeaning meaning = OffsetMeaning::OntoProfile);

//! The reference evaluates every segment at every vertex of the level, serially; the optimized
//! one gathers each segment's neighbourhood by a walk over the mesh and evaluates in parallel.
//! They agree exactly (same segments, same order). \throw FlatnessError (see ray_unrolling.h).
LevelPerturbation compute_perturbation(const TriangleSurface& s, const std::vector<BaseCurve>& curves,
                                       Backend backend);

//! compute_perturbation at the given vertices only (the region a design step changed): the same
//! offsets there, the cost of the vertices given. The result lists those a segment moves, sorted.
LevelPerturbation perturb_vertices(const TriangleSurface& s, const std::vector<BaseCurve>& curves,
                                   std::vector<int> vertices, Backend backend);

//! The features' displacement (OffsetMeaning::Displacement, combined as on the level) of
//! arbitrary points near the level: the vertices of a finer level or their limit points.
//! `vertices` of the result index the rows of `points`. Same back ends, same exact agreement.
LevelPerturbation displace_points(const TriangleSurface& s, const std::vector<BaseCurve>& curves,
                                  const MatrixX3& points, Backend backend);

}  // namespace fairshape::feature
