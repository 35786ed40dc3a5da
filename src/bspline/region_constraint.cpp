#include "fairshape/bspline/region_constraint.h"

#include <algorithm>
#include <cmath>

#include "fairshape/bspline/knot_basis.h"
#include "fairshape/bspline/uniform_basis.h"
#include "fairshape/core/error.h"

namespace fairshape::bspline {

namespace {

void check_region(const HierarchicalSurface& s, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  check_in_domain(s, lo.x(), lo.y(), "region constraint, first corner");
  check_in_domain(s, hi.x(), hi.y(), "region constraint, second corner");
  if (!(hi.x() > lo.x()) || !(hi.y() > lo.y()))
    throw InvalidInput("region constraint: the rectangle is empty (its second corner must be above its first in u and in v)");
}

// [a, b] cut at every line of a grid `grid` lines per base span.
std::vector<double> cuts(double a, double b, double grid) {
  std::vector<double> out{a};
  for (double line = std::floor(a * grid) + 1; line < b * grid; line += 1) out.push_back(line / grid);
  out.push_back(b);
  return out;
}

}  // namespace

void for_each_region_sample(const HierarchicalSurface& s, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, int per_cell,
                            const std::function<void(double u, double v)>& visit) {
  const double grid = std::ldexp(1.0, s.level_count() - 1);
  const std::vector<double> us = cuts(lo.x(), hi.x(), grid), vs = cuts(lo.y(), hi.y(), grid);
  for (std::size_t a = 0; a + 1 < us.size(); ++a)
    for (std::size_t b = 0; b + 1 < vs.size(); ++b)
      for (int i = 0; i <= per_cell; ++i)
        for (int j = 0; j <= per_cell; ++j)
          visit(us[a] + (us[a + 1] - us[a]) * i / per_cell, vs[b] + (vs[b + 1] - vs[b]) * j / per_cell);
}

ConstraintRows region_rows(const HierarchicalSurface& s, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                           const SurfaceTrace& traced, const Vec3& shift) {
  check_region(s, lo, hi);
  if (!shift.allFinite()) throw InvalidInput("region constraint: the shift is not finite");
  // Both surfaces and the multipliers are one polynomial per finest cell of either: ψ b_k and
  // ψ W have degree ≤ 2r per direction, r + 1 Gauss points are exact.
  const double grid = std::ldexp(1.0, std::max(s.level_count(), traced.surface.level_count()) - 1);
  const int r = std::max(s.degree(), traced.surface.degree());
  const GaussRule g = gauss_legendre(r + 1);
  const std::vector<double> us = cuts(lo.x(), hi.x(), grid), vs = cuts(lo.y(), hi.y(), grid);
  // The multipliers: tensor B-splines of degree r clamped to R, with a knot at every finest grid
  // line inside it (the mortar rule of the curves, mortar_curve.h).
  const ClampedKnotBasis U(lo.x(), hi.x(), std::vector<double>(us.begin() + 1, us.end() - 1), r);
  const ClampedKnotBasis V(lo.y(), hi.y(), std::vector<double>(vs.begin() + 1, vs.end() - 1), r);
  const int nv = V.size(), m = U.size() * nv;
  Triplets t;
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(m, 3);
  BasisRow row;
  std::vector<double> pu, pv;
  int fu = 0, fv = 0;
  for (std::size_t a = 0; a + 1 < us.size(); ++a)
    for (std::size_t b = 0; b + 1 < vs.size(); ++b) {
      const double hu = us[a + 1] - us[a], hv = vs[b + 1] - vs[b];
      for (std::size_t qa = 0; qa < g.nodes.size(); ++qa)
        for (std::size_t qb = 0; qb < g.nodes.size(); ++qb) {
          const double u = us[a] + g.nodes[qa] * hu, v = vs[b] + g.nodes[qb] * hv;
          const double w = g.weights[qa] * g.weights[qb] * hu * hv;
          const Vec3 W = traced.surface.position(traced.P, u, v) + shift;
          s.basis(u, v, row);
          U.evaluate(u, fu, pu);
          V.evaluate(v, fv, pv);
          for (std::size_t i = 0; i < pu.size(); ++i)
            for (std::size_t j = 0; j < pv.size(); ++j) {
              const double wij = w * pu[i] * pv[j];
              if (wij == 0) continue;
              const int k = (fu + static_cast<int>(i)) * nv + fv + static_cast<int>(j);
              C.row(k) += wij * W.transpose();
              for (const BasisEntry& e : row) t.emplace_back(k, e.dof, wij * e.value);
            }
        }
    }
  ConstraintRows out;
  out.A.resize(m, s.dof_count());
  out.A.setFromTriplets(t.begin(), t.end());
  // Each row divided by ∫ψ: a weighted mean of w over R, its residual a distance.
  Eigen::VectorXd inverse_mass(m);
  for (int i = 0; i < U.size(); ++i)
    for (int j = 0; j < nv; ++j) inverse_mass[i * nv + j] = 1.0 / (U.integral(i) * V.integral(j));
  out.A = inverse_mass.asDiagonal() * out.A;
  out.C = inverse_mass.asDiagonal() * C;
  return out;
}

}  // namespace fairshape::bspline
