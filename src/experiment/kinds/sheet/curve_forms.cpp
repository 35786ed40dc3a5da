#include "fairshape/experiment/kinds/sheet/curve_forms.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>

#include <Eigen/Geometry>

#include "fairshape/core/message_format.h"
#include "fairshape/core/types.h"
#include "fairshape/curves/curve_sampling.h"

namespace fairshape {
namespace {

template <int D>
using Point = Eigen::Matrix<double, D, 1>;

struct Samples {
  Eigen::MatrixXd X;  // one point per row, equally spaced in t
  bool closed = false;
};

const char* point_spelling(int d) { return d == 2 ? "[u, v]" : "[x, y, z]"; }
std::string where(const Config& c) { return c.path().empty() ? std::string("curve") : c.path(); }

template <int D>
Point<D> to_point(const std::vector<double>& v, const std::string& key_path) {
  if (v.size() != D)
    throw InvalidConfig(key_path + ": expected " + point_spelling(D) + ", got " + std::to_string(v.size()) + " numbers");
  return Eigen::Map<const Point<D>>(v.data());
}

template <int D>
Point<D> read_point(Config& c, const std::string& key, const std::string& doc) {
  const auto v = c.require<std::vector<double>>(key, doc);
  return c.documenting() ? Point<D>::Zero() : to_point<D>(v, c.key_path(key));
}

// Rows of an n × D matrix; `too_few` completes "at least N points, got M" with why.
template <int D>
Eigen::MatrixXd read_point_list(Config& c, const std::string& key, std::size_t at_least, const std::string& too_few,
                                const std::string& doc) {
  const auto list = c.require<std::vector<std::vector<double>>>(key, doc);
  if (c.documenting()) return Eigen::MatrixXd(0, D);
  if (list.size() < at_least)
    throw InvalidConfig(c.key_path(key) + ": at least " + std::to_string(at_least) + " points" + too_few + ", got " +
                        std::to_string(list.size()));
  Eigen::MatrixXd out(static_cast<Eigen::Index>(list.size()), D);
  for (std::size_t k = 0; k < list.size(); ++k)
    out.row(static_cast<Eigen::Index>(k)) = to_point<D>(list[k], c.key_path(key) + "[" + std::to_string(k) + "]").transpose();
  return out;
}

// `samples`, when given; a closed curve needs a fourth point, its last repeating its first.
std::optional<int> read_samples(Config& c, bool closed) {
  const int n = c.get_int("samples", kDefaultCurveSamples, 2, kMaxCurveSamples,
                          "points the curve is sampled into, equally spaced in t (absent: a polyline keeps its vertices, "
                          "arcs and B-splines give " + std::to_string(kDefaultCurveSamples) + ")");
  if (!c.has("samples")) return std::nullopt;
  if (closed && n < 4)
    throw InvalidConfig(c.key_path("samples") + ": a closed curve needs at least 4 points (its last repeats its first), got " +
                        std::to_string(n));
  return n;
}

template <int D>
Samples read_polyline(Config& c, double chord_tolerance) {
  const bool closed = c.get<bool>("closed", false, "the curve returns to its first point (points and bspline)");
  const Eigen::MatrixXd V = read_point_list<D>(c, "points", closed ? 3 : 2, closed ? " (closed)" : "",
                                               std::string("polyline ") + "[" + point_spelling(D) + ", ...]");
  const std::optional<int> samples = read_samples(c, closed);
  if (c.documenting()) return {V, closed};
  if (closed && V.row(0) == V.row(V.rows() - 1))
    throw InvalidConfig(c.key_path("points") + ": the last point repeats the first; closed: true adds the closing segment "
                        "itself (give each point once)");
  if (!samples) {  // the vertices are the points, t stepping evenly from one to the next
    if (!closed) return {V, false};
    Eigen::MatrixXd loop(V.rows() + 1, D);
    loop << V, V.row(0);
    return {loop, true};
  }
  double length = closed ? (V.row(0) - V.row(V.rows() - 1)).norm() : 0;
  for (Eigen::Index i = 1; i < V.rows(); ++i) length += (V.row(i) - V.row(i - 1)).norm();
  if (!(length > 0))
    throw InvalidConfig(c.key_path("points") + ": all points coincide: a curve of zero length has no arc length to resample by "
                        "(samples)");
  const Eigen::MatrixXd resampled = resample_polyline(V, closed, *samples);
  // Resampling in arc length cuts the given corners; with a chord tolerance (what the curve must
  // be met to) a count that cuts one by more is refused, as for arcs.
  if (chord_tolerance > 0) {
    double worst = 0;
    for (Eigen::Index i = 0; i < V.rows(); ++i) {
      double nearest = std::numeric_limits<double>::infinity();
      for (Eigen::Index k = 0; k + 1 < resampled.rows(); ++k) {
        const Eigen::RowVectorXd a = resampled.row(k), ab = resampled.row(k + 1) - a;
        const double t = ab.squaredNorm() > 0 ? std::clamp((V.row(i) - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
        nearest = std::min(nearest, (V.row(i) - (a + t * ab)).norm());
      }
      worst = std::max(worst, nearest);
    }
    if (worst > chord_tolerance)
      throw InvalidConfig(c.key_path("samples") + ": " + std::to_string(*samples) + " samples cut a corner of the polyline by " +
                          sci(worst) + ", above refinement.tolerance " + sci(chord_tolerance) +
                          " (refinement could never meet it): give more, or leave samples out to keep the vertices");
  }
  return {resampled, closed};
}

// Orthonormal axes of a space arc's plane: `axes` (the second made orthogonal to the first) or
// `normal`, whose first axis is the world axis least aligned with it, projected (normal
// [0, 0, 1]: x and y, like a (u, v) arc).
void read_space_arc_axes(Config& a, CircleArc& arc) {
  if (a.has("normal") && a.has("axes")) throw InvalidConfig(a.key_path("axes") + ": give normal or axes, not both");
  if (a.has("axes")) {
    const auto axes = a.get<std::vector<std::vector<double>>>("axes", {}, "[[first axis], [second axis]]: angle 0 along the first");
    if (axes.size() != 2) throw InvalidConfig(a.key_path("axes") + ": expected two axes [[x, y, z], [x, y, z]]");
    const Vec3 a1 = to_point<3>(axes[0], a.key_path("axes") + "[0]"), a2 = to_point<3>(axes[1], a.key_path("axes") + "[1]");
    const Vec3 e2 = a2 - a2.dot(a1) / a1.squaredNorm() * a1;
    if (a1.norm() == 0 || !(e2.norm() > 1e-9 * a2.norm()))
      throw InvalidConfig(a.key_path("axes") + ": the two axes must be nonzero and not parallel");
    arc.e1 = a1.normalized();
    arc.e2 = e2.normalized();
    return;
  }
  const std::vector<double> nv = a.get<std::vector<double>>("normal", {0, 0, 1}, "normal of the arc's plane (or give axes)");
  const Vec3 n = to_point<3>(nv, a.key_path("normal"));
  if (!(n.norm() > 0)) throw InvalidConfig(a.key_path("normal") + ": must be nonzero");
  const Vec3 u = n.normalized();
  Eigen::Index least = 0;
  u.cwiseAbs().minCoeff(&least);
  const Vec3 e1 = (Vec3::Unit(least) - u[least] * u).normalized();
  arc.e1 = e1;
  arc.e2 = u.cross(e1);
}

// The largest distance between a sampling's chords and the exact curve at their middles: a
// sampler equally spaced in t gives the middles of n samples as the odd rows of 2n − 1.
double chord_error(const std::function<Eigen::MatrixXd(int)>& sample, int n) {
  const Eigen::MatrixXd X = sample(n), fine = sample(2 * n - 1);
  double worst = 0;
  for (Eigen::Index k = 0; k + 1 < X.rows(); ++k)
    worst = std::max(worst, (fine.row(2 * k + 1) - 0.5 * (X.row(k) + X.row(k + 1))).norm());
  return worst;
}

// The sample count of an analytic form (arc, B-spline). Without a chord tolerance: the given
// count or the default. With one (refinement.tolerance): a given count whose chord error exceeds
// it is refused (refinement could never go below it), and the default count is doubled until the
// chord error is a quarter of it.
int analytic_samples(Config& c, const std::optional<int>& given, double chord_tolerance,
                     const std::function<Eigen::MatrixXd(int)>& sample) {
  if (!(chord_tolerance > 0)) return given.value_or(kDefaultCurveSamples);
  if (given) {
    const double e = chord_error(sample, *given);
    if (e > chord_tolerance) {
      int enough = *given;
      while (enough < kMaxCurveSamples && chord_error(sample, enough) > 0.25 * chord_tolerance) enough = 2 * enough - 1;
      throw InvalidConfig(c.key_path("samples") + ": " + std::to_string(*given) + " samples leave a chord error of " +
                          sci(e) + ", above refinement.tolerance " + sci(chord_tolerance) +
                          " (refinement could never meet it): give about " + std::to_string(enough) +
                          ", or leave samples out to have them chosen");
    }
    return *given;
  }
  int n = kDefaultCurveSamples;
  while (chord_error(sample, n) > 0.25 * chord_tolerance) {
    if (2 * n - 1 > kMaxCurveSamples)
      throw InvalidConfig(where(c) + ": even " + std::to_string(n) + " samples leave a chord error above a quarter of "
                          "refinement.tolerance " + sci(chord_tolerance));
    n = 2 * n - 1;
  }
  return n;
}

template <int D>
Samples read_arc(Config& c, double chord_tolerance) {
  if (c.has("closed"))
    throw InvalidConfig(c.key_path("closed") + ": not for an arc (an arc is closed when to_angle - from_angle = ±360)");
  Config a = c.child("arc", std::string("circle arc {center, radius, from_angle, to_angle") + (D == 3 ? ", normal | axes}" : "}"));
  CircleArc arc;
  arc.center = read_point<D>(a, "center", std::string("center ") + point_spelling(D));
  arc.radius = a.require<double>("radius", "radius (> 0)");
  if (!a.documenting() && !(arc.radius > 0))
    throw InvalidConfig(a.key_path("radius") + ": must be positive, got " + format_default(arc.radius));
  arc.from_deg = a.get<double>("from_angle", 0, "start angle in degrees (0 along the first axis, 90 along the second)");
  arc.to_deg = a.get<double>("to_angle", arc.from_deg + 360, "end angle in degrees (default from_angle + 360: a full circle)");
  const double sweep = std::abs(arc.to_deg - arc.from_deg);
  if (!a.documenting() && (sweep == 0 || (sweep > 360 && !arc.full_circle())))
    throw InvalidConfig(a.key_path("to_angle") + ": the arc must turn by more than 0 and at most 360 degrees, got " +
                        format_default(sweep));
  if constexpr (D == 3) {
    read_space_arc_axes(a, arc);
  } else {
    arc.e1 = Eigen::Vector2d::UnitX();  // angle 0 along u, 90 along v
    arc.e2 = Eigen::Vector2d::UnitY();
  }
  a.check_no_unknown_keys();
  const std::optional<int> samples = read_samples(c, arc.full_circle());
  if (a.documenting()) return {Eigen::MatrixXd(0, D), false};
  const auto sample = [&](int n) { return sample_arc(arc, n); };
  return {sample(analytic_samples(c, samples, chord_tolerance, sample)), arc.full_circle()};
}

template <int D>
Samples read_bspline(Config& c, double chord_tolerance) {
  const bool closed = c.get<bool>("closed", false, "the curve returns to its first point (points and bspline)");
  Config b = c.child("bspline", "B-spline {degree, control_points, knots}");
  const int degree = b.get_int("degree", 3, 1, kMaxCurveDegree, "polynomial degree");
  const int at_least = closed ? std::max(degree + 1, 3) : degree + 1;
  const Eigen::MatrixXd P =
      read_point_list<D>(b, "control_points", static_cast<std::size_t>(at_least),
                         " for a" + std::string(closed ? " closed" : "") + " B-spline of degree " + std::to_string(degree),
                         std::string("control points [") + point_spelling(D) + ", ...]");
  BSplineCurve curve;
  if (b.has("knots")) {
    if (closed)
      throw InvalidConfig(b.key_path("knots") + ": a closed B-spline has evenly spaced periodic knots; leave knots out");
    curve.knots = b.get<std::vector<double>>("knots", {}, "non-decreasing, control points + degree + 1 of them");
    const std::string problem = bspline_knot_problem(static_cast<int>(P.rows()), degree, curve.knots);
    if (!problem.empty()) throw InvalidConfig(b.key_path("knots") + ": " + problem);
  } else {
    (void)b.get<std::vector<double>>("knots", {}, "non-decreasing, control points + degree + 1 of them (default: uniform clamped)");
  }
  b.check_no_unknown_keys();
  const std::optional<int> samples = read_samples(c, closed);
  if (b.documenting()) return {Eigen::MatrixXd(0, D), closed};
  if (closed) {
    curve = periodic_bspline(P, degree);
  } else {
    curve.degree = degree;
    curve.control = P;
    if (curve.knots.empty()) curve.knots = uniform_clamped_knots(static_cast<int>(P.rows()), degree);
  }
  const auto sample = [&](int n) { return sample_bspline(curve, n); };
  return {sample(analytic_samples(c, samples, chord_tolerance, sample)), closed};
}

const std::vector<std::string> kForms{"points", "arc", "bspline"};

}  // namespace

bool has_curve_form_key(const Config& c) {
  for (const char* k : {"points", "closed", "arc", "bspline", "samples"})
    if (c.has(k)) return true;
  return false;
}

template <int D>
SampledCurve<D> read_curve_form(Config& c, double chord_tolerance) {
  std::vector<std::string> given;
  for (const std::string& f : kForms)
    if (c.has(f)) given.push_back(f);
  if (given.size() > 1)
    throw InvalidConfig(c.key_path(given[1]) + ": give one of points, arc, bspline (" + given[0] + " is given too)");
  if (given.empty() && !c.documenting()) throw InvalidConfig(where(c) + ": a curve needs one of points, arc, bspline");
  const std::string form = given.empty() ? "points" : given[0];
  const Samples s = form == "points" ? read_polyline<D>(c, chord_tolerance) : form == "arc" ? read_arc<D>(c, chord_tolerance)
                                                                                 : read_bspline<D>(c, chord_tolerance);
  SampledCurve<D> out;
  for (Eigen::Index i = 0; i < s.X.rows(); ++i) out.points.push_back(s.X.row(i).transpose());
  out.closed = s.closed;
  return out;
}

template SampledCurve<2> read_curve_form<2>(Config& c, double chord_tolerance);
template SampledCurve<3> read_curve_form<3>(Config& c, double chord_tolerance);

SampledCurve<2> read_uv_curve(Config& c, const std::string& key, const std::string& doc, double chord_tolerance) {
  const YAML::Node n = c.node()[key];
  if (!c.has(key) || n.IsSequence()) {  // a plain list: the polyline's vertices, as they are
    (void)c.get<std::vector<std::vector<double>>>(key, {}, doc + ": [[u, v], ...] or {points | arc | bspline, closed, samples}");
    SampledCurve<2> out;
    if (!c.has(key)) return out;
    const Eigen::MatrixXd V = read_point_list<2>(c, key, 2, "", doc);
    for (Eigen::Index i = 0; i < V.rows(); ++i) out.points.push_back(V.row(i).transpose());
    return out;
  }
  if (!n.IsMap())
    throw InvalidConfig(c.key_path(key) + ": expected [[u, v], ...] or a curve {points | arc | bspline, closed, samples}, got '" +
                        yaml_to_string(n) + "'");
  Config sub = c.child(key, doc);
  SampledCurve<2> out = read_curve_form<2>(sub, chord_tolerance);
  sub.check_no_unknown_keys();
  return out;
}

}  // namespace fairshape
