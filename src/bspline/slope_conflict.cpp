#include "fairshape/bspline/slope_conflict.h"

#include <algorithm>
#include <cmath>

#include "fairshape/bspline/surface_constraints.h"
#include "fairshape/core/message_format.h"

namespace fairshape::bspline {
namespace {

bool derivative_kind(const SheetConstraint& c) {
  return c.kind == SheetConstraint::Kind::Tangent || c.kind == SheetConstraint::Kind::Normal;
}

// The curve's slope along its path at t: the space curve's change over the path's length in
// design units, taken centred over one sample spacing of the finer polyline (second order on a
// sampled smooth curve, where a one-sided chord would differ by the curvature times a spacing),
// and the path's unit direction there.
SlopeMismatch curve_slope(const SheetConstraint& c, double t, const Eigen::Vector2d& span_size) {
  const std::size_t n = std::max(c.curve.uv.size(), c.curve.space.size());
  const double delta = 1.0 / static_cast<double>(n - 1);
  const double t0 = std::max(0.0, t - delta), t1 = std::min(1.0, t + delta);
  const Eigen::Vector2d step = (polyline_at(c.curve.uv, t1) - polyline_at(c.curve.uv, t0)).cwiseProduct(span_size);
  SlopeMismatch out;
  const double length = step.norm();
  if (!(length > 0)) return out;  // a path standing still: no direction to compare along
  out.direction = step / length;
  out.curve_slope = (polyline_at(c.curve.space, t1) - polyline_at(c.curve.space, t0)) / length;
  return out;
}

}  // namespace

std::optional<SlopeMismatch> slope_conflict(const std::vector<SheetConstraint>& constraints, const Eigen::Vector2d& span_size,
                                            double on_path, double tolerance) {
  const std::vector<Coincidence> shared = coincidences(constraints, on_path);
  std::optional<SlopeMismatch> worst;
  for (const Coincidence& c : shared) {
    const SheetConstraint& other = constraints[static_cast<std::size_t>(c.other)];
    if (!derivative_kind(other)) continue;
    // Unknowns: J's columns [D_u w; D_v w] (design units). Every condition at this point is a
    // slope, so the residual of the least-squares J is one too.
    std::vector<Eigen::Matrix<double, 1, 6>> rows;
    std::vector<double> rhs;
    const auto add = [&](const Eigen::Matrix<double, 1, 6>& r, double b) { rows.push_back(r), rhs.push_back(b); };
    SlopeMismatch first;
    bool any_curve = false;
    for (const Coincidence& k : shared) {  // every curve through this point
      if (k.other != c.other) continue;
      const SlopeMismatch s = curve_slope(constraints[static_cast<std::size_t>(k.curve)], k.t, span_size);
      if (s.direction.isZero()) continue;
      if (!any_curve) first = s, first.at = k;
      any_curve = true;
      for (int i = 0; i < 3; ++i) {
        Eigen::Matrix<double, 1, 6> r = Eigen::Matrix<double, 1, 6>::Zero();
        r[i] = s.direction.x(), r[3 + i] = s.direction.y();
        add(r, s.curve_slope[i]);
      }
    }
    if (!any_curve) continue;
    const Eigen::Vector2d p(other.u, other.v);
    for (const SheetConstraint& d : constraints) {  // every tangent and normal at this point
      if (!derivative_kind(d) || (Eigen::Vector2d(d.u, d.v) - p).norm() > on_path) continue;
      if (d.kind == SheetConstraint::Kind::Tangent) {
        for (int i = 0; i < 3; ++i) {
          Eigen::Matrix<double, 1, 6> r = Eigen::Matrix<double, 1, 6>::Zero();
          r[3 * d.direction + i] = 1;
          add(r, d.target[i]);
        }
      } else {
        const Vec3 n = d.target.normalized();
        for (int col = 0; col < 2; ++col) {
          Eigen::Matrix<double, 1, 6> r = Eigen::Matrix<double, 1, 6>::Zero();
          r.segment<3>(3 * col) = n.transpose();
          add(r, 0);
        }
      }
    }
    Eigen::MatrixXd M(static_cast<Eigen::Index>(rows.size()), 6);
    Eigen::VectorXd b(static_cast<Eigen::Index>(rows.size()));
    for (std::size_t i = 0; i < rows.size(); ++i) M.row(static_cast<Eigen::Index>(i)) = rows[i], b[static_cast<Eigen::Index>(i)] = rhs[i];
    const Eigen::VectorXd J = M.completeOrthogonalDecomposition().solve(b);
    const double mismatch = (M * J - b).norm();
    if (!(mismatch > tolerance) || (worst && !(mismatch > worst->at.gap))) continue;
    worst = first;
    worst->at.other = c.other;
    worst->at.gap = mismatch;
  }
  return worst;
}

std::string describe(const SlopeMismatch& m, const std::vector<SheetConstraint>& constraints, const Eigen::Vector2d& span_size) {
  const auto name = [&](int k) {
    const std::string& l = constraints[static_cast<std::size_t>(k)].label;
    return l.empty() ? "constraint " + std::to_string(k) : l;
  };
  const SheetConstraint& o = constraints[static_cast<std::size_t>(m.at.other)];
  const Eigen::Vector2d uv = m.at.uv.cwiseProduct(span_size);
  const std::string kind = o.kind == SheetConstraint::Kind::Tangent ? " (a tangent)" : " (a normal)";
  return name(m.at.other) + kind + " lies on the path of curve " + name(m.at.curve) + " at (u, v) = (" + sci(uv.x()) + ", " +
         sci(uv.y()) + "), t = " + sci(m.at.t) + ", where the curve asks the slope (" + sci(m.curve_slope.x()) + ", " +
         sci(m.curve_slope.y()) + ", " + sci(m.curve_slope.z()) + ") along its path: no surface has both derivatives (they " +
         "differ by " + sci(m.at.gap) + " in slope)";
}

}  // namespace fairshape::bspline
