// The curves of sheet configs, read from a config block in any of their forms and sampled into
// points equally spaced in t ∈ [0, 1] (src/curves/curve_sampling.h): space curves (`curves:`
// entries, 3-D) and the (u, v) curves of curve constraints and of from_surface (2-D).
//   points: [[...], ...]        a polyline; with `closed: true` it returns to its first point
//                               (give each point once: the closing segment is implied)
//   arc: {center, radius, from_angle, to_angle}     degrees, 0 along the first axis, 90 along
//                               the second; to − from = ±360 is a full, closed circle. Space
//                               arcs lie in the plane of `normal` (default [0, 0, 1]) or of
//                               `axes: [[...], [...]]` (angle 0 along the first)
//   bspline: {degree, control_points, knots}        knots default to uniform clamped (the curve
//                               starts and ends at the end control points); `closed: true`
//                               makes a periodic uniform B-spline of the control loop instead
//   samples: N                  how many points the curve is sampled into, for every form
// Without `samples` a polyline keeps its vertices as its points (t steps evenly from vertex to
// vertex, which is what plain point lists always meant), and arcs and B-splines give
// kDefaultCurveSamples points. With it, a polyline is resampled equally in arc length, an arc
// equally in angle, a B-spline equally in its knot parameter. Closed curves' last point repeats
// their first, and `samples` counts it. Values pass through unchanged: the module does not
// know (u, v) units.
// With a chord tolerance (a sheet run's refinement.tolerance: what the curve must be met to),
// arcs and B-splines without `samples` are sampled until their chords are within a quarter of
// it of the exact curve, and a `samples` that leaves more than the tolerance is refused: the
// sampled polyline is the target, so refinement could never get below its chord error.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "fairshape/core/config.h"

namespace fairshape {

inline constexpr int kDefaultCurveSamples = 65;
inline constexpr int kMaxCurveSamples = 100000;
inline constexpr int kMaxCurveDegree = 9;

template <int D>
struct SampledCurve {
  std::vector<Eigen::Matrix<double, D, 1>> points;  // equally spaced in t; closed: back() == front()
  bool closed = false;
};

//! True when the block holds a key of a curve form (points, closed, arc, bspline, samples).
bool has_curve_form_key(const Config& c);

//! The curve the form keys of block `c` describe: exactly one of points, arc, bspline, with
//! optional closed and samples. The block may hold other keys (a space curve's name, edits):
//! its reader checks for unknown keys; the arc and bspline maps are checked here.
//! \throw InvalidConfig naming the key path: no form or two, a point of the wrong dimension,
//! too few points, radius ≤ 0, an arc of 0° or more than 360°, a degree out of range, too few
//! control points, knots of the wrong count or order, samples out of range or too few for
//! chord_tolerance (see above).
template <int D>
SampledCurve<D> read_curve_form(Config& c, double chord_tolerance = 0);

//! The (u, v) curve under `key`: a plain list [[u, v], ...] (a polyline keeping its vertices,
//! as before) or a map of form keys ({arc: {...}, samples: 33}). Empty when the key is absent.
SampledCurve<2> read_uv_curve(Config& c, const std::string& key, const std::string& doc, double chord_tolerance = 0);

}  // namespace fairshape
