#include "fairshape/curve_design/explicit_length.h"

#include "fairshape/core/backend.h"
#if FAIRSHAPE_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#endif

#include <Eigen/Geometry>
#include <cmath>

#include "fairshape/core/error.h"

namespace fairshape {
namespace {

// Moves `moving` towards `fixed` so their distance is at most `reach`.
bool pull_in(const MatrixX3& pts, int fixed, int moving, double reach, MatrixX3& out) {
  const Eigen::RowVector3d d = pts.row(moving) - pts.row(fixed);
  const double s = d.norm();
  if (s <= reach) return false;
  out.row(moving) = pts.row(fixed) + d * (reach / s);
  return true;
}

int shorten_stretched_segments(MatrixX3& c, const Eigen::VectorXd& target, bool closed, int anchor) {
  const int m = static_cast<int>(c.rows()), segments = closed ? m : m - 1;
  const auto reach = [&](int seg) { return target[2 * seg] + target[2 * seg + 1]; };
  int forward = closed ? segments / 2 : m - 1 - anchor, backward = closed ? segments - 1 - forward : anchor;
  int count = 0;
  for (int k = 0; k < forward; ++k) {
    const int i = (anchor + k) % m;
    count += pull_in(c, i, (i + 1) % m, reach(i), c);
  }
  for (int k = 0; k < backward; ++k) {
    const int i = (anchor - k + m) % m, prev = (i - 1 + m) % m;
    count += pull_in(c, i, prev, reach(prev), c);
  }
  return count;
}

Vec3 any_perpendicular(const Vec3& u) {
  const Vec3 left = Vec3::UnitZ().cross(u);  // the left normal of a curve in the xy plane
  if (left.norm() > 1e-9) return left.normalized();
  return u.cross(Vec3::UnitX()).normalized();
}

}  // namespace

bool place_midpoint(const MatrixX3& c, MatrixX3& detail, const Eigen::VectorXd& target, int i) {
  const int m = static_cast<int>(c.rows());
  const Vec3 P = c.row(i).transpose(), Q = c.row((i + 1) % m).transpose();
  const Vec3 mid = 0.5 * (P + Q), current = mid + detail.row(i).transpose();
  const double a = target[2 * i], b = target[2 * i + 1], s = (Q - P).norm();
  const Vec3 u = s > 0 ? Vec3((Q - P) / s) : Vec3::UnitX();
  double t = s >= a + b ? a * s / (a + b) : (a * a - b * b + s * s) / (2 * s);
  t = std::clamp(t, -a, a);
  const double h = std::sqrt(std::max(0.0, a * a - t * t));
  Vec3 side = (current - P) - (current - P).dot(u) * u;
  side = side.norm() > 1e-12 * std::max(s, a) ? Vec3(side.normalized()) : any_perpendicular(u);
  const Vec3 apex = P + t * u + h * side;
  const bool changed = (apex - current).norm() > 1e-12 * (a + b);
  detail.row(i) = (apex - mid).transpose();
  return changed;
}

int count_unplaceable_midpoints(const MatrixX3& c, const Eigen::VectorXd& target, bool closed) {
  const int m = static_cast<int>(c.rows()), segments = closed ? m : m - 1;
  int count = 0;
  for (int i = 0; i < segments; ++i) {
    const double a = target[2 * i], b = target[2 * i + 1], s = (c.row((i + 1) % m) - c.row(i)).norm();
    count += s < std::abs(a - b) * (1 - 1e-12);
  }
  return count;
}

ExplicitLengthReport preserve_lengths_explicitly(MatrixX3& coarse, MatrixX3& detail, const Eigen::VectorXd& target,
                                                 bool closed, int anchor, Backend backend) {
  const int segments = static_cast<int>(detail.rows());
  FAIRSHAPE_ASSERT(target.size() == 2 * segments, "two target lengths per level-w segment");
  FAIRSHAPE_ASSERT(anchor >= 0 && anchor < coarse.rows(), "anchor on the level-w polygon");
  ExplicitLengthReport rep;
  require_backend(backend);
  rep.shortened_segments = shorten_stretched_segments(coarse, target, closed, anchor);
#if FAIRSHAPE_WITH_TBB
  if (backend == Backend::Reference) {
    for (int i = 0; i < segments; ++i) rep.moved_midpoints += place_midpoint(coarse, detail, target, i);
  } else {
    rep.moved_midpoints = tbb::parallel_reduce(
        tbb::blocked_range<int>(0, segments, 4096), 0,
        [&](const tbb::blocked_range<int>& r, int n) {
          for (int i = r.begin(); i != r.end(); ++i) n += place_midpoint(coarse, detail, target, i);
          return n;
        },
        std::plus<int>());
  }
#else
  for (int i = 0; i < segments; ++i) rep.moved_midpoints += place_midpoint(coarse, detail, target, i);
#endif
  return rep;
}

}  // namespace fairshape
