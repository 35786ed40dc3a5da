#include "fairshape/curve_design/explicit_local.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "fairshape/core/error.h"

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

// A level-e segment's chain can reach only if its ends are at most Σr apart. When the edit put
// moved control points farther, they are pulled back along the chord (both halves when both
// ends moved), alternating over the chains until every chain reaches: each step projects onto
// one ball |P_a − P_b| ≤ R, and the balls of an edit that started from a curve of these lengths
// intersect, so the projections converge. Returns the largest pull-back.
double pull_back_moved(MatrixX3& c, const Eigen::VectorXd& target, const std::set<int>& chains, const std::set<int>& moved,
                       int stride, int segments_e, bool closed, int& unresolved) {
  const int m = static_cast<int>(c.rows());
  std::map<int, Vec3> start;
  for (int i : moved) start[i] = c.row((i * stride) % m).transpose();
  const auto reach = [&](int j) {
    double r = 0;
    for (int k = 0; k < stride; ++k) r += target[2 * (j * stride + k)] + target[2 * (j * stride + k) + 1];
    return r;
  };
  const auto end_of = [&](int j) { return closed ? (j + 1) % segments_e : j + 1; };
  for (int round = 0; round < 10000; ++round) {
    bool changed = false;
    for (int j : chains) {
      const int a = j, b = end_of(j), pa = (a * stride) % m, pb = (b * stride) % m;
      const Vec3 d = (c.row(pb) - c.row(pa)).transpose();
      const double R = reach(j), len = d.norm();
      if (len <= R * (1 + kStretchSlack)) continue;
      const bool ma = moved.count(a) > 0, mb = moved.count(b) > 0;
      const Vec3 u = d / len;
      const double excess = len - R;
      if (ma && mb) {
        c.row(pa) += (0.5 * excess * u).transpose();
        c.row(pb) -= (0.5 * excess * u).transpose();
      } else if (mb) {
        c.row(pb) -= (excess * u).transpose();
      } else if (ma) {
        c.row(pa) += (excess * u).transpose();
      }
      changed = true;
    }
    if (!changed) break;
  }
  unresolved = 0;
  for (int j : chains) {
    const int pa = (j * stride) % m, pb = (end_of(j) * stride) % m;
    unresolved += (c.row(pb) - c.row(pa)).norm() > reach(j) * (1 + kStretchSlack);
  }
  double worst = 0;
  for (const auto& [i, x] : start) worst = std::max(worst, (c.row((i * stride) % m).transpose() - x).norm());
  return worst;
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
  std::set<int> moved;
  for (int i : moved_e) moved.insert(i);
  int unresolved = 0;
  rep.worst_pull_back = pull_back_moved(coarse, target, chains, moved, stride, segments_e, closed, unresolved);
  (void)unresolved;  // fix_chain counts what is left, with the excess
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
