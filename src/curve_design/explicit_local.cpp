#include "curve_design/explicit_local.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "core/error.h"

namespace fairshape {
namespace {

// Segments stretched by less than this (relative) count as reaching: a straight reference is
// only equal to a + b up to rounding.
constexpr double kStretchSlack = 1e-12;

// The least t in [0, 1] with |d + t(e − d)| ≤ r, given |e| ≤ r (g(t) = |·|² − r² is convex).
double least_blend(const Vec3& d, const Vec3& e, double r) {
  const double C = d.squaredNorm() - r * r;
  if (C <= 0) return 0;
  const Vec3 v = e - d;
  const double A = v.squaredNorm(), B = 2 * d.dot(v);
  if (A <= 0) return 1;
  const double disc = std::max(0.0, B * B - 4 * A * C);
  // g(0) > 0 ≥ g(1): the smaller root lies in (0, 1]; this form has no cancellation for B < 0.
  const double t = 2 * C / (-B + std::sqrt(disc));
  return std::clamp(std::isfinite(t) ? t : 1.0, 0.0, 1.0);
}

struct ChainResult {
  bool stretched = false, unreachable = false;
  double excess = 0;
};

// Level-w points first..first+stride (indices mod m), ends fixed.
ChainResult fix_chain(MatrixX3& c, const Eigen::VectorXd& target, int first, int stride) {
  const int m = static_cast<int>(c.rows());
  const auto at = [&](int k) { return (first + k) % m; };
  const auto reach = [&](int k) { return target[2 * at(k)] + target[2 * at(k) + 1]; };
  ChainResult out;
  for (int k = 0; k < stride; ++k)
    out.stretched |= (c.row(at(k + 1)) - c.row(at(k))).norm() > reach(k) * (1 + kStretchSlack);
  if (!out.stretched) return out;
  // The straight chain: the chord cut in proportion to the reaches.
  double total = 0;
  for (int k = 0; k < stride; ++k) total += reach(k);
  const Vec3 start = c.row(at(0)).transpose(), chord = (c.row(at(stride)) - c.row(at(0))).transpose();
  std::vector<Vec3> straight(static_cast<std::size_t>(stride + 1));
  double so_far = 0;
  for (int k = 0; k <= stride; ++k) {
    straight[static_cast<std::size_t>(k)] = k == stride ? Vec3(c.row(at(stride)).transpose()) : Vec3(start + chord * (so_far / total));
    if (k < stride) so_far += reach(k);
  }
  double t = 1;
  if (chord.norm() > total * (1 + kStretchSlack)) {
    out.unreachable = true;
    out.excess = chord.norm() / total - 1;
  } else {
    t = 0;
    for (int k = 0; k < stride; ++k) {
      const Vec3 d = (c.row(at(k + 1)) - c.row(at(k))).transpose();
      const Vec3 e = straight[static_cast<std::size_t>(k + 1)] - straight[static_cast<std::size_t>(k)];
      t = std::max(t, least_blend(d, e, reach(k)));
    }
  }
  for (int k = 1; k < stride; ++k) {
    const Vec3 p = c.row(at(k)).transpose();
    c.row(at(k)) = (p + t * (straight[static_cast<std::size_t>(k)] - p)).transpose();
  }
  return out;
}

}  // namespace

ExplicitLengthReport preserve_lengths_locally(MatrixX3& coarse, MatrixX3& detail, const Eigen::VectorXd& target,
                                              bool closed, const std::vector<int>& moved_e, int stride) {
  const int m = static_cast<int>(coarse.rows()), segments = static_cast<int>(detail.rows());
  FAIRSHAPE_ASSERT(target.size() == 2 * segments, "two target lengths per level-w segment");
  const int segments_e = segments / stride;
  // Level-e segments next to a moved control point: the support's chains.
  std::set<int> chains;
  for (int i : moved_e)
    for (int j : {i - 1, i}) {
      if (closed) chains.insert(((j % segments_e) + segments_e) % segments_e);
      else if (j >= 0 && j < segments_e) chains.insert(j);
    }
  ExplicitLengthReport rep;
  for (int j : chains) {
    const ChainResult r = fix_chain(coarse, target, j * stride, stride);
    rep.shortened_segments += r.stretched ? stride : 0;
    rep.unreachable_chains += r.unreachable;
    rep.worst_excess = std::max(rep.worst_excess, r.excess);
  }
  for (int j : chains)
    for (int k = 0; k < stride; ++k) rep.moved_midpoints += place_midpoint(coarse, detail, target, (j * stride + k) % m);
  return rep;
}

}  // namespace fairshape
