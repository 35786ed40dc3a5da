#include "fairshape/curves/curve_sampling.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "fairshape/core/error.h"

namespace fairshape {

Eigen::MatrixXd resample_polyline(const Eigen::MatrixXd& vertices, bool closed, int samples) {
  const Eigen::Index n = vertices.rows();
  FAIRSHAPE_ASSERT(n >= (closed ? 3 : 2) && samples >= (closed ? 4 : 2), "resample_polyline: too few vertices or samples");
  Eigen::MatrixXd path(closed ? n + 1 : n, vertices.cols());
  path.topRows(n) = vertices;
  if (closed) path.row(n) = vertices.row(0);
  std::vector<double> s(path.rows(), 0.0);  // arc length at each vertex
  for (Eigen::Index i = 1; i < path.rows(); ++i) s[i] = s[i - 1] + (path.row(i) - path.row(i - 1)).norm();
  const double length = s.back();
  FAIRSHAPE_ASSERT(length > 0, "resample_polyline: a path of zero length has no arc length parameter");

  Eigen::MatrixXd out(samples, vertices.cols());
  std::size_t seg = 0;  // the path segment [seg, seg + 1] holding the current sample
  for (int k = 0; k < samples; ++k) {
    const double target = length * k / (samples - 1);
    while (seg + 2 < s.size() && s[seg + 1] < target) ++seg;
    const double ds = s[seg + 1] - s[seg];
    const double w = ds > 0 ? std::clamp((target - s[seg]) / ds, 0.0, 1.0) : 0.0;
    out.row(k) = (1 - w) * path.row(seg) + w * path.row(seg + 1);
  }
  // The ends exactly where the path's are (no rounding from the last division).
  out.row(0) = path.row(0);
  out.row(samples - 1) = path.row(path.rows() - 1);
  return out;
}

bool CircleArc::full_circle() const { return std::abs(std::abs(to_deg - from_deg) - 360) < 1e-9; }

Eigen::MatrixXd sample_arc(const CircleArc& arc, int samples) {
  FAIRSHAPE_ASSERT(samples >= (arc.full_circle() ? 4 : 2), "sample_arc: too few samples");
  Eigen::MatrixXd out(samples, arc.center.size());
  for (int k = 0; k < samples; ++k) {
    const double a = (arc.from_deg + (arc.to_deg - arc.from_deg) * k / (samples - 1)) * M_PI / 180;
    out.row(k) = (arc.center + arc.radius * (std::cos(a) * arc.e1 + std::sin(a) * arc.e2)).transpose();
  }
  if (arc.full_circle()) out.row(samples - 1) = out.row(0);  // closed exactly, not up to rounding
  return out;
}

std::vector<double> uniform_clamped_knots(int control_points, int degree) {
  FAIRSHAPE_ASSERT(degree >= 1 && control_points >= degree + 1, "uniform_clamped_knots: too few control points");
  std::vector<double> knots(static_cast<std::size_t>(degree + 1), 0.0);
  const int spans = control_points - degree;
  for (int i = 1; i < spans; ++i) knots.push_back(static_cast<double>(i) / spans);
  knots.insert(knots.end(), static_cast<std::size_t>(degree + 1), 1.0);
  return knots;
}

BSplineCurve periodic_bspline(const Eigen::MatrixXd& control, int degree) {
  FAIRSHAPE_ASSERT(degree >= 1 && control.rows() >= degree + 1, "periodic_bspline: too few control points");
  BSplineCurve c;
  c.degree = degree;
  c.closed = true;
  // Rotated by degree / 2 so that t = 0 is the blend centred on the first control point (odd
  // degrees; halfway between the first two for even ones), like a clamped curve starting there.
  const Eigen::Index n = control.rows(), shift = degree / 2;
  c.control.resize(n + degree, control.cols());
  for (Eigen::Index i = 0; i < n + degree; ++i) c.control.row(i) = control.row(((i - shift) % n + n) % n);
  // Evenly spaced knots 0, 1, ...: the domain [degree, rows] starts and ends at the same
  // blend of the same control points, so the loop closes with the curve's full smoothness.
  for (Eigen::Index i = 0; i < c.control.rows() + degree + 1; ++i) c.knots.push_back(static_cast<double>(i));
  return c;
}

std::string bspline_knot_problem(int control_points, int degree, const std::vector<double>& knots) {
  const std::size_t expected = static_cast<std::size_t>(control_points + degree + 1);
  if (knots.size() != expected)
    return "expected " + std::to_string(expected) + " knots (control points + degree + 1), got " + std::to_string(knots.size());
  for (std::size_t i = 1; i < knots.size(); ++i)
    if (!(knots[i] >= knots[i - 1]))
      return "knot " + std::to_string(i) + " is below knot " + std::to_string(i - 1) + ": knots must be non-decreasing";
  const double lo = knots[degree], hi = knots[control_points];
  if (!(lo < hi)) return "the parameter domain [knots[degree], knots[control points]] is empty";
  std::map<double, int> multiplicity;
  for (double k : knots) ++multiplicity[k];
  for (const auto& [value, count] : multiplicity) {
    // degree + 1 equal knots inside the domain make the curve jump there.
    const int allowed = value > lo && value < hi ? degree : degree + 1;
    std::ostringstream v;
    v << value;
    if (count > allowed)
      return "knot " + v.str() + " repeated " + std::to_string(count) + " times: at most " +
             std::to_string(allowed) + (allowed == degree ? " inside the domain, or the curve breaks apart" : "");
  }
  return "";
}

Eigen::VectorXd bspline_point(const BSplineCurve& curve, double x) {
  const int p = curve.degree, n = static_cast<int>(curve.control.rows());
  const std::vector<double>& U = curve.knots;
  FAIRSHAPE_ASSERT(bspline_knot_problem(n, p, U).empty(), "bspline_point: invalid knots");
  // The span [U[k], U[k+1]) holding x; the domain's right end belongs to the last non-empty span.
  int k = p;
  while (k + 1 < n && U[k + 1] <= x && U[k + 1] < U[n]) ++k;
  // De Boor: p rounds of convex combinations of the p + 1 control points that act on the span.
  std::vector<Eigen::VectorXd> d;
  for (int j = 0; j <= p; ++j) d.push_back(curve.control.row(j + k - p).transpose());
  for (int r = 1; r <= p; ++r)
    for (int j = p; j >= r; --j) {
      const double lo = U[j + k - p], hi = U[j + 1 + k - r];  // hi − lo ≥ U[k+1] − U[k] > 0
      const double alpha = (x - lo) / (hi - lo);
      d[j] = (1 - alpha) * d[j - 1] + alpha * d[j];
    }
  return d[p];
}

Eigen::MatrixXd sample_bspline(const BSplineCurve& curve, int samples) {
  FAIRSHAPE_ASSERT(samples >= (curve.closed ? 4 : 2), "sample_bspline: too few samples");
  const double lo = curve.knots[curve.degree], hi = curve.knots[curve.control.rows()];
  Eigen::MatrixXd out(samples, curve.control.cols());
  for (int k = 0; k < samples; ++k) out.row(k) = bspline_point(curve, lo + (hi - lo) * k / (samples - 1)).transpose();
  if (curve.closed) out.row(samples - 1) = out.row(0);  // closed exactly, not up to rounding
  return out;
}

}  // namespace fairshape
