#include "fairshape/bspline/constraint_coincidence.h"

#include <algorithm>
#include <cmath>

#include "fairshape/bspline/surface_constraints.h"
#include "fairshape/core/message_format.h"

namespace fairshape::bspline {
namespace {

using Path = std::vector<Eigen::Vector2d>;

bool weak_curve(const SheetConstraint& c) { return c.kind == SheetConstraint::Kind::Curve && c.formulation == CurveFormulation::Mortar; }

// The parameter of segment k at fraction s, as polyline_at reads it (uniform in the vertex index).
double path_t(const Path& uv, std::size_t k, double s) { return (static_cast<double>(k) + s) / static_cast<double>(uv.size() - 1); }

struct Nearest {
  double distance = INFINITY, t = 0;
};

// The point of the path nearest p.
Nearest nearest_on(const Path& uv, const Eigen::Vector2d& p) {
  Nearest best;
  for (std::size_t k = 0; k + 1 < uv.size(); ++k) {
    const Eigen::Vector2d ab = uv[k + 1] - uv[k];
    const double len2 = ab.squaredNorm();
    const double s = len2 > 0 ? std::clamp((p - uv[k]).dot(ab) / len2, 0.0, 1.0) : 0.0;
    const double d = (p - (uv[k] + s * ab)).norm();
    if (d < best.distance) best = {d, path_t(uv, k, s)};
  }
  return best;
}

// Parameters (t on a, t on b) of the points two paths share: proper crossings of their
// segments, and every vertex of one within on_path of the other (touching ends, overlaps).
std::vector<std::pair<double, double>> shared_points(const Path& a, const Path& b, double on_path) {
  std::vector<std::pair<double, double>> out;
  for (std::size_t i = 0; i + 1 < a.size(); ++i)
    for (std::size_t j = 0; j + 1 < b.size(); ++j) {
      const Eigen::Vector2d r = a[i + 1] - a[i], s = b[j + 1] - b[j], q = b[j] - a[i];
      const double cross = r.x() * s.y() - r.y() * s.x();
      if (std::abs(cross) <= 1e-14 * r.norm() * s.norm()) continue;  // parallel: the vertex tests below
      const double x = (q.x() * s.y() - q.y() * s.x()) / cross, y = (q.x() * r.y() - q.y() * r.x()) / cross;
      if (x >= 0 && x <= 1 && y >= 0 && y <= 1) out.emplace_back(path_t(a, i, x), path_t(b, j, y));
    }
  // A vertex's own parameter is its index's (nearest_on on its own path could pick another
  // stretch where the path comes back near itself).
  for (std::size_t k = 0; k < a.size(); ++k) {
    const Nearest n = nearest_on(b, a[k]);
    if (n.distance <= on_path) out.emplace_back(path_t(a, k, 0), n.t);
  }
  for (std::size_t k = 0; k < b.size(); ++k) {
    const Nearest n = nearest_on(a, b[k]);
    if (n.distance <= on_path) out.emplace_back(n.t, path_t(b, k, 0));
  }
  return out;
}

}  // namespace

std::vector<Coincidence> coincidences(const std::vector<SheetConstraint>& constraints, double on_path) {
  std::vector<Coincidence> out;
  const auto add = [&](std::size_t curve, std::size_t other, double t, const Vec3* asked_there) {
    const SheetConstraint& c = constraints[curve];
    const double gap = asked_there ? (curve_target_at(c.curve, t) - *asked_there).norm() : 0.0;
    out.push_back({static_cast<int>(curve), static_cast<int>(other), polyline_at(c.curve.uv, t), t, gap});
  };
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    if (!weak_curve(constraints[i])) continue;
    const Path& path = constraints[i].curve.uv;
    for (std::size_t j = 0; j < constraints.size(); ++j) {
      const SheetConstraint& o = constraints[j];
      if (j == i) continue;
      if (o.kind == SheetConstraint::Kind::Curve) {
        if (j < i && weak_curve(o)) continue;  // each weak pair once
        for (const auto& [ti, tj] : shared_points(path, o.curve.uv, on_path)) {
          const Vec3 there = curve_target_at(o.curve, tj);
          add(i, j, ti, &there);
        }
        continue;
      }
      const Nearest n = nearest_on(path, Eigen::Vector2d(o.u, o.v));
      if (n.distance <= on_path) add(i, j, n.t, o.kind == SheetConstraint::Kind::Point ? &o.target : nullptr);
    }
  }
  return out;
}

std::optional<Coincidence> conflicting_coincidence(const std::vector<SheetConstraint>& constraints, double on_path,
                                                   double tolerance) {
  std::optional<Coincidence> worst;
  for (const Coincidence& c : coincidences(constraints, on_path))
    if (c.gap > tolerance && (!worst || c.gap > worst->gap)) worst = c;
  return worst;
}

std::string describe(const Coincidence& c, const std::vector<SheetConstraint>& constraints, const Eigen::Vector2d& span_size) {
  const auto name = [&](int k) {
    const std::string& l = constraints[static_cast<std::size_t>(k)].label;
    return l.empty() ? "constraint " + std::to_string(k) : l;
  };
  const SheetConstraint& o = constraints[static_cast<std::size_t>(c.other)];
  static const char* const kinds[] = {" (a point)", " (a tangent)", " (a normal)", " (a curve)"};
  const Eigen::Vector2d uv = c.uv.cwiseProduct(span_size);
  return name(c.other) + kinds[static_cast<int>(o.kind)] + " lies on the path of curve " +
         name(c.curve) + " at (u, v) = (" + sci(uv.x()) + ", " + sci(uv.y()) + "), t = " + sci(c.t) +
         ", and asks a position " + sci(c.gap) + " away from the curve's there: no surface meets both";
}

}  // namespace fairshape::bspline
