#include "fairshape/bspline/hierarchical_curve_basis.h"

#include <algorithm>
#include <cmath>

#include <Eigen/QR>

#include "fairshape/bspline/uniform_basis.h"
#include "fairshape/core/error.h"

namespace fairshape::bspline {

double single_bspline(const std::vector<double>& knots, double x) {
  const int r = static_cast<int>(knots.size()) - 2;
  FAIRSHAPE_ASSERT(r >= 0, "a B-spline has at least two knots");
  // Cox–de Boor on the r + 1 degree-0 pieces, raised one degree at a time (0/0 counts as 0).
  std::vector<double> N(static_cast<std::size_t>(r + 1));
  for (int j = 0; j <= r; ++j) N[j] = knots[j] <= x && x < knots[j + 1] ? 1.0 : 0.0;
  for (int p = 1; p <= r; ++p)
    for (int j = 0; j + p <= r; ++j) {
      const double left = knots[j + p] > knots[j] ? (x - knots[j]) / (knots[j + p] - knots[j]) * N[j] : 0.0;
      const double right =
          knots[j + p + 1] > knots[j + 1] ? (knots[j + p + 1] - x) / (knots[j + p + 1] - knots[j + 1]) * N[j + 1] : 0.0;
      N[j] = left + right;
    }
  return N[0];
}

HierarchicalCurveBasis::HierarchicalCurveBasis(int spans, int degree)
    : spans_(spans), degree_(degree), knots_(0, 1, {}, std::max(degree, 0)) {
  if (spans < 1 || spans > kMaxSpans)
    throw InvalidInput("variational curve: spans must lie in [1, " + std::to_string(kMaxSpans) + "], got " + std::to_string(spans));
  if (degree < kMinDegree || degree > kMaxDegree)
    throw InvalidInput("variational curve: degree " + std::to_string(degree) + " outside [" + std::to_string(kMinDegree) + ", " +
                       std::to_string(kMaxDegree) + "]");
  omega_.emplace_back();
  for (int s = 0; s < spans; ++s) omega_[0].insert(omega_[0].end(), s);
  rebuild();
}

void HierarchicalCurveBasis::support(const Function& f, int& first, int& last) const {
  // Clamped uniform knots τ_j = clamp((j − r) / n): function i spans knot intervals i..i+r,
  // i.e. layer spans i − r .. i, clipped to the layer.
  first = std::max(0, f.index - degree_);
  last = std::min(spans(f.level) - 1, f.index);
}

std::vector<double> HierarchicalCurveBasis::function_knots(const Function& f) const {
  const double n = spans(f.level);
  std::vector<double> out;
  for (int j = f.index; j <= f.index + degree_ + 1; ++j) out.push_back(std::clamp((j - degree_) / n, 0.0, 1.0));
  return out;
}

bool HierarchicalCurveBasis::support_in(const Function& f, int level) const {
  if (level >= level_count()) return false;
  int first = 0, last = 0;
  support(f, first, last);
  const int scale = 1 << (level - f.level);  // the support's spans on `level`
  const std::set<int>& omega = omega_[level];
  for (int s = first * scale; s < (last + 1) * scale; ++s)
    if (!omega.count(s)) return false;
  return true;
}

const CurveSpan& HierarchicalCurveBasis::leaf_cell_at(double t) const {
  const auto it = std::upper_bound(leaves_.begin(), leaves_.end(), t, [](double x, const CurveSpan& c) { return x < c.t0; });
  return it == leaves_.begin() ? leaves_.front() : *std::prev(it);
}

void HierarchicalCurveBasis::rebuild() {
  const int r = degree_;
  // Kraft's selection: in Ω_L, not spanned by layer L + 1.
  dofs_.clear();
  for (int L = 0; L < level_count(); ++L) {
    std::set<int> candidates;
    for (int s : omega_[L])
      for (int i = s; i <= s + r; ++i) candidates.insert(i);
    for (int i : candidates) {
      const Function f{L, i};
      if (support_in(f, L) && !support_in(f, L + 1)) dofs_.push_back(f);
    }
  }
  // Leaf cells, coarse to fine in t order: a span whose children are in Ω_{L+1} is replaced by them.
  leaves_.clear();
  const auto add_leaves = [&](const auto& self, int L, int s) -> void {
    if (L + 1 < level_count() && omega_[L + 1].count(2 * s)) {
      self(self, L + 1, 2 * s);
      self(self, L + 1, 2 * s + 1);
      return;
    }
    const double n = spans(L);
    leaves_.push_back({L, s, s / n, (s + 1) / n});
  };
  for (int s = 0; s < spans_; ++s) add_leaves(add_leaves, 0, s);
  leaves_.back().t1 = 1;

  std::vector<double> interior;
  for (std::size_t k = 1; k < leaves_.size(); ++k) interior.push_back(leaves_[k].t0);
  knots_ = ClampedKnotBasis(0, 1, interior, r);
  // U: the knot basis's full knot vector, to find the knot functions inside a support.
  std::vector<double> U(static_cast<std::size_t>(r + 1), 0.0);
  U.insert(U.end(), interior.begin(), interior.end());
  U.insert(U.end(), static_cast<std::size_t>(r + 1), 1.0);

  // R: each hierarchical function in the knot basis. It is a spline on those knots with
  // support [a, b], so exactly the knot functions whose support lies in [a, b] represent it;
  // their coefficients are the least-squares fit at r + 1 Gauss points of every leaf in [a, b]
  // (exact: the function is in their span).
  const GaussRule g = gauss_legendre(r + 1);
  Triplets t;
  std::vector<double> values;
  for (int k = 0; k < dof_count(); ++k) {
    const std::vector<double> fk = function_knots(dofs_[k]);
    const double a = fk.front(), b = fk.back();
    const int j0 = static_cast<int>(std::lower_bound(U.begin(), U.end(), a) - U.begin());
    int j1 = j0;  // one past the last knot function with τ_{j+r+1} ≤ b
    while (j1 + r + 1 < static_cast<int>(U.size()) && U[j1 + r + 1] <= b) ++j1;
    FAIRSHAPE_ASSERT(j1 > j0, "a hierarchical function covers at least one knot function");
    std::vector<double> x;
    for (const CurveSpan& leaf : leaves_)
      if (leaf.t0 >= a && leaf.t1 <= b)
        for (double node : g.nodes) x.push_back(leaf.t0 + node * (leaf.t1 - leaf.t0));
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(x.size()), j1 - j0);
    Eigen::VectorXd rhs(static_cast<Eigen::Index>(x.size()));
    for (std::size_t p = 0; p < x.size(); ++p) {
      int first = 0;
      knots_.evaluate(x[p], first, values);
      for (std::size_t i = 0; i < values.size(); ++i) {
        const int j = first + static_cast<int>(i);
        if (j >= j0 && j < j1) M(static_cast<Eigen::Index>(p), j - j0) = values[i];
      }
      rhs[static_cast<Eigen::Index>(p)] = single_bspline(fk, x[p]);
    }
    const Eigen::VectorXd c = M.colPivHouseholderQr().solve(rhs);
    FAIRSHAPE_ASSERT((M * c - rhs).cwiseAbs().maxCoeff() < 1e-10, "a hierarchical function is a spline on the leaf knots");
    for (int j = j0; j < j1; ++j)
      if (c[j - j0] != 0) t.emplace_back(j, k, c[j - j0]);
  }
  R_.resize(knots_.size(), dof_count());
  R_.setFromTriplets(t.begin(), t.end());
  R_.prune(0.0, 1e-14);
}

int HierarchicalCurveBasis::refine(const std::vector<CurveSpan>& cells) {
  // Every cell is checked before any is refined (widening one may cover its neighbour).
  for (const CurveSpan& cell : cells) {
    const int L = cell.level;
    const bool leaf = L < level_count() && omega_[L].count(cell.index) &&
                      !(L + 1 < level_count() && omega_[L + 1].count(2 * cell.index));
    if (!leaf)
      throw InvalidInput("variational curve: span " + std::to_string(cell.index) + " of layer " + std::to_string(L) +
                         " is not a leaf cell");
    if (L + 1 > kMaxLevel) throw InvalidInput("variational curve: layer " + std::to_string(L + 1) + " is beyond the deepest, " +
                                              std::to_string(kMaxLevel));
  }
  int added = 0;
  for (const CurveSpan& cell : cells) {
    const int L = cell.level;
    if (L + 1 == level_count()) omega_.emplace_back();
    std::set<int>& fine = omega_[L + 1];
    const int n = spans(L + 1);
    for (int s = std::max(0, 2 * cell.index - degree_); s <= std::min(n - 1, 2 * cell.index + 1 + degree_); ++s) {
      if (!omega_[L].count(s / 2)) continue;  // Ω_{L+1} stays inside the children of Ω_L
      // Whole parents: both children, so the leaves tile [0, 1].
      added += static_cast<int>(fine.insert(s).second) + static_cast<int>(fine.insert(s ^ 1).second);
    }
  }
  rebuild();
  return added;
}

}  // namespace fairshape::bspline
