#include "fairshape/bspline/mortar_curve.h"

#include <algorithm>
#include <cmath>

#include "fairshape/bspline/knot_basis.h"
#include "fairshape/bspline/uniform_basis.h"
#include "fairshape/core/error.h"

namespace fairshape::bspline {

namespace {

// The uv polyline by arc length: vertex k at S[k] (its points are equally spaced in t).
struct ArcLength {
  std::vector<double> S;
  explicit ArcLength(const std::vector<Eigen::Vector2d>& uv) : S{0.0} {
    for (std::size_t k = 0; k + 1 < uv.size(); ++k) S.push_back(S.back() + (uv[k + 1] - uv[k]).norm());
  }
  double length() const { return S.back(); }
  // t ∈ [0, 1] of arc length s (the segment's t is linear in its s).
  double t_of(double s) const {
    const std::size_t n = S.size() - 1;
    std::size_t k = static_cast<std::size_t>(std::upper_bound(S.begin(), S.end(), s) - S.begin());
    k = std::clamp<std::size_t>(k, 1, n) - 1;
    while (k + 1 < n && S[k + 1] - S[k] <= 0) ++k;
    const double len = S[k + 1] - S[k];
    const double a = len > 0 ? std::clamp((s - S[k]) / len, 0.0, 1.0) : 0.0;
    return (static_cast<double>(k) + a) / static_cast<double>(n);
  }
  double s_of(double t) const {
    const double x = std::clamp(t, 0.0, 1.0) * static_cast<double>(S.size() - 1);
    const std::size_t k = std::min(static_cast<std::size_t>(x), S.size() - 2);
    return S[k] + (x - static_cast<double>(k)) * (S[k + 1] - S[k]);
  }
};

// Gauss rule g on every piece between consecutive breaks (arc length, clamped to [0, L]; pieces
// shorter than rounding skipped): visit(s, weight) at each point. Both integrations along a curve
// (the joint's rows, the tangent-continuity rows) run on it.
template <class Visit>
void for_each_gauss_point(const std::vector<double>& breaks, double L, const GaussRule& g, Visit visit) {
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double s0 = std::clamp(breaks[k], 0.0, L), s1 = std::clamp(breaks[k + 1], 0.0, L);
    if (s1 - s0 <= 1e-14 * L) continue;
    for (std::size_t q = 0; q < g.nodes.size(); ++q) visit(s0 + g.nodes[q] * (s1 - s0), g.weights[q] * (s1 - s0));
  }
}

// The finest level whose unknowns are nonzero at (u, v): the surface's resolution there.
int resolution_at(const HierarchicalSurface& s, const Eigen::Vector2d& uv, BasisRow& row) {
  s.basis(uv.x(), uv.y(), row);
  int level = 0;
  for (const BasisEntry& e : row) level = std::max(level, s.dofs()[static_cast<std::size_t>(e.dof)].level);
  return level;
}

// Crossings (arc length) of the finest grid's lines of `axis` on segment k, with each line's
// finest index g (the line is one of level m for every m with g divisible by 2^(F−m)).
template <class Visit>
void grid_crossings(const std::vector<Eigen::Vector2d>& uv, const ArcLength& arc, std::size_t k, int axis, double grid,
                    Visit visit) {
  const double a = uv[k][axis] * grid, b = uv[k + 1][axis] * grid;
  if (a == b) return;
  for (double line = std::ceil(std::min(a, b)); line <= std::max(a, b); line += 1)
    visit(arc.S[k] + (line - a) / (b - a) * (arc.S[k + 1] - arc.S[k]), static_cast<long long>(line));
}

// The coarsest level of which finest-grid line g is a line (F: the finest level).
int line_level(long long g, int F) {
  int m = F;
  while (m > 0 && g % 2 == 0) g /= 2, --m;
  return m;
}

Eigen::Vector2d uv_at(const std::vector<Eigen::Vector2d>& uv, const ArcLength& arc, double s) {
  return polyline_at(uv, arc.t_of(s));
}

// The (u, v) curve ends where it starts: the same point, or once round a periodic u.
bool closes(const HierarchicalSurface& s, const std::vector<Eigen::Vector2d>& uv) {
  const Eigen::Vector2d d = uv.back() - uv.front();
  const double tol = 1e-9 * std::max(s.shape().spans_u, s.shape().spans_v);
  if (d.norm() <= tol) return true;
  if (!s.shape().periodic_u || std::abs(d.y()) > tol) return false;
  const double turns = d.x() / s.shape().spans_u;
  return std::abs(turns) > 0.5 && std::abs(turns - std::round(turns)) * s.shape().spans_u <= tol;
}

}  // namespace

std::vector<double> mortar_knots(const HierarchicalSurface& s, const std::vector<Eigen::Vector2d>& uv) {
  const ArcLength arc(uv);
  const int F = s.level_count() - 1;
  const double grid = std::ldexp(1.0, F), L = arc.length();
  BasisRow row;
  std::vector<double> knots;
  double last = 0;
  for (std::size_t k = 0; k + 1 < uv.size(); ++k) {
    const Eigen::Vector2d d = uv[k + 1] - uv[k];
    const int axis = std::abs(d.x()) >= std::abs(d.y()) ? 0 : 1;
    grid_crossings(uv, arc, k, axis, grid, [&](double sk, long long g) {
      // The resolution on either side of the line: a knot of a level the surface has there.
      const double eps = 1e-7 / grid;
      const int res = std::max(resolution_at(s, uv_at(uv, arc, std::max(sk - eps, 0.0)), row),
                               resolution_at(s, uv_at(uv, arc, std::min(sk + eps, L)), row));
      if (line_level(g, F) > res) return;
      // Knots closer than half a cell to the previous one (where the dominant direction
      // changes) or a quarter cell to an end would make nearly dependent multipliers.
      const double h = std::ldexp(1.0, -res);
      const double gap = knots.empty() ? 0.25 * h : 0.5 * h;
      if (sk - last < gap || L - sk < 0.25 * h) return;
      knots.push_back(sk);
      last = sk;
    });
  }
  return knots;
}

ClampedKnotBasis polyline_basis(std::size_t points) {
  FAIRSHAPE_ASSERT(points >= 2, "a polyline has at least two points");
  const double n = static_cast<double>(points - 1);
  std::vector<double> interior;
  for (std::size_t k = 1; k + 1 < points; ++k) interior.push_back(static_cast<double>(k) / n);
  return ClampedKnotBasis(0, 1, interior, 1);
}

namespace {
void check_uv_curve(const HierarchicalSurface& s, const std::vector<Eigen::Vector2d>& uv) {
  if (uv.size() < 2) throw InvalidInput("curve constraint: needs at least two (u, v) points");
  for (std::size_t k = 0; k < uv.size(); ++k) check_in_domain(s, uv[k].x(), uv[k].y(), "curve constraint, (u, v) point " + std::to_string(k));
  if (!(ArcLength(uv).length() > 0)) throw InvalidInput("curve constraint: the (u, v) curve has zero length");
}

// The surface-trace multipliers along uv (arc length L) on `knots` (mortar_knots): clamped B-splines
// of the surface's degree, or periodic ones for a closed curve, whose trace is periodic: clamped
// multipliers would pair r functions too many with it (dependent rows, and targets that disagree
// at the closure by their discretization).
ClampedKnotBasis trace_multipliers(const HierarchicalSurface& s, const std::vector<Eigen::Vector2d>& uv, double L,
                                   std::vector<double>& knots) {
  const int r = s.degree();
  if (!closes(s, uv)) return ClampedKnotBasis(0, L, knots, r);
  knots.insert(knots.begin(), 0.0);
  if (static_cast<int>(knots.size()) < r + 1) {  // shorter than r + 1 cells: evenly spaced
    knots.clear();
    for (int k = 0; k <= r; ++k) knots.push_back(L * k / (r + 1));
  }
  return ClampedKnotBasis::periodic(0, L, knots, r);
}
}  // namespace

int mortar_multiplier_count(const HierarchicalSurface& s, const std::vector<Eigen::Vector2d>& uv) {
  check_uv_curve(s, uv);
  std::vector<double> knots = mortar_knots(s, uv);
  return trace_multipliers(s, uv, ArcLength(uv).length(), knots).size();
}

namespace {
// mortar_rows, and with `traced` also ∫ψ_j traced(c(s)) ds / ∫ψ_j into *traced_means (m × 3): a
// target that is the surface a curve was traced on, integrated exactly like the rows (its
// grid's crossings are breaks too; along a straight piece it is a polynomial of degree ≤ 2r).
MortarRows mortar_rows_with(const HierarchicalSurface& s, const std::vector<Eigen::Vector2d>& uv, const ClampedKnotBasis& target,
                            Multipliers multipliers, const SparseMatrix* target_map, const SurfaceTrace* traced,
                            Eigen::MatrixXd* traced_means) {
  check_uv_curve(s, uv);
  const ArcLength arc(uv);
  const double L = arc.length();
  const int r = s.degree();
  std::vector<double> knots = mortar_knots(s, uv);
  const ClampedKnotBasis W = trace_multipliers(s, uv, L, knots);
  const bool on_target = multipliers == Multipliers::Target;
  // ψ_j(s): W's functions in the arc length, or the target's in t(s).
  const auto multipliers_at = [&](double sq, double tq, int& first, std::vector<double>& psi) {
    if (on_target) target.evaluate(tq, first, psi);
    else W.evaluate(sq, first, psi);
  };

  // Pieces on which the integrand is one polynomial: between uv vertices, the target's knots
  // (in t), W's knots and every finest grid line crossed.
  std::vector<double> breaks = arc.S;
  for (double tk : target.breaks()) breaks.push_back(arc.s_of(tk));
  breaks.insert(breaks.end(), knots.begin(), knots.end());
  const double grid = std::ldexp(1.0, std::max(s.level_count(), traced ? traced->surface.level_count() : 0) - 1);
  for (std::size_t k = 0; k + 1 < uv.size(); ++k)
    for (int axis = 0; axis < 2; ++axis) grid_crossings(uv, arc, k, axis, grid, [&](double sk, long long) { breaks.push_back(sk); });
  std::sort(breaks.begin(), breaks.end());

  // ψ · the surface's basis along a straight piece (degree ≤ 2r) and ψ · the target's basis
  // (t is linear in s on a piece): an exact Gauss rule for the higher (at least 3r + 1).
  const int psi_degree = on_target ? target.degree() : r;
  const int degree = std::max(3 * r + 1, psi_degree + std::max(2 * r, target.degree()));
  const GaussRule g = gauss_legendre(degree / 2 + 1);
  const int m = on_target ? target.size() : W.size();
  Triplets ta, tb;
  Eigen::VectorXd mass = Eigen::VectorXd::Zero(m);  // ∫ψ_j ds: each row is divided by it
  BasisRow row;
  std::vector<double> psi, x;
  int first = 0, first_x = 0;
  Eigen::MatrixXd means = Eigen::MatrixXd::Zero(traced ? m : 0, 3);
  for_each_gauss_point(breaks, L, g, [&](double sq, double w) {
    const double tq = arc.t_of(sq);
    const Eigen::Vector2d c = polyline_at(uv, tq);
    s.basis(c.x(), c.y(), row);
    target.evaluate(tq, first_x, x);
    multipliers_at(sq, tq, first, psi);
    const Vec3 traced_here = traced ? Vec3(traced->surface.position(traced->P, c.x(), c.y())) : Vec3::Zero();
    for (std::size_t a = 0; a < psi.size(); ++a) {
      const double wa = w * psi[a];
      if (wa == 0) continue;
      const int j = (first + static_cast<int>(a)) % m;  // a periodic W's functions wrap round
      mass[j] += wa;
      if (traced) means.row(j) += wa * traced_here.transpose();
      for (const BasisEntry& e : row) ta.emplace_back(j, e.dof, wa * e.value);
      for (std::size_t i = 0; i < x.size(); ++i) tb.emplace_back(j, first_x + static_cast<int>(i), wa * x[i]);
    }
  });
  MortarRows out;
  out.A.resize(m, s.dof_count());
  out.A.setFromTriplets(ta.begin(), ta.end());
  out.B.resize(m, target.size());
  out.B.setFromTriplets(tb.begin(), tb.end());
  if (target_map) {
    out.B = out.B * *target_map;
    if (on_target) {  // the multipliers Σ_i R_ij T_i: rows (and their masses) combined by Rᵀ
      const SparseMatrix Rt = target_map->transpose();
      out.A = Rt * out.A;
      out.B = Rt * out.B;
      mass = Rt * mass;
    }
  }
  const Eigen::VectorXd inverse_mass = mass.cwiseInverse();
  out.A = inverse_mass.asDiagonal() * out.A;
  out.B = inverse_mass.asDiagonal() * out.B;
  if (traced) *traced_means = inverse_mass.asDiagonal() * means;
  return out;
}
}  // namespace

MortarRows mortar_rows(const HierarchicalSurface& s, const std::vector<Eigen::Vector2d>& uv, const ClampedKnotBasis& target,
                       Multipliers multipliers, const SparseMatrix* target_map) {
  return mortar_rows_with(s, uv, target, multipliers, target_map, nullptr, nullptr);
}

ConstraintRows mortar_curve_rows(const HierarchicalSurface& s, const CurveAttachment& curve) {
  check_curve_attachment(s, curve);
  // The fixed space curve is the target whose coefficients are known: its points, on the hat
  // functions of a polyline equally spaced in t.
  // A traced target: the traced surface itself along the path (its means, exact) plus the
  // polyline of the edits' offsets at the samples.
  Eigen::MatrixXd traced_means;
  MortarRows rows = mortar_rows_with(s, curve.uv, polyline_basis(curve.space.size()), Multipliers::SurfaceTrace, nullptr,
                                     curve.traced.get(), &traced_means);
  Eigen::MatrixXd D(static_cast<Eigen::Index>(curve.space.size()), 3);
  const double last = static_cast<double>(curve.space.size() - 1);
  for (std::size_t k = 0; k < curve.space.size(); ++k) {
    Vec3 d = curve.space[k];
    if (curve.traced) {
      const Eigen::Vector2d c = polyline_at(curve.uv, static_cast<double>(k) / last);
      d -= curve.traced->surface.position(curve.traced->P, c.x(), c.y());
    }
    D.row(static_cast<Eigen::Index>(k)) = d.transpose();
  }
  ConstraintRows out;
  out.C = rows.B * D;
  if (curve.traced) out.C += traced_means;
  out.A = std::move(rows.A);
  return out;
}

namespace {

// The unit (u, v) normal of uv's segment at t pointing out of the kept side, in design units,
// as the factors of ∂/∂u and ∂/∂v in base-span units.
Eigen::Vector2d outward_factors(const JointSide& side, double t) {
  const Eigen::Vector2d h = side.surface->shape().span_size;
  const std::size_t n = side.uv.size() - 1;
  std::size_t k = std::min(static_cast<std::size_t>(std::clamp(t, 0.0, 1.0) * static_cast<double>(n)), n - 1);
  while (k + 1 < n && (side.uv[k + 1] - side.uv[k]).norm() == 0) ++k;  // a repeated point has no direction
  const Eigen::Vector2d d = (side.uv[k + 1] - side.uv[k]).cwiseProduct(h).normalized();
  const Eigen::Vector2d left(-d.y(), d.x());
  const Eigen::Vector2d out = side.keep_left ? Eigen::Vector2d(-left) : left;
  return out.cwiseQuotient(h);
}

}  // namespace

Vec3 outward_derivative(const JointSide& side, const Eigen::MatrixXd& P, double t) {
  const Eigen::Vector2d c = polyline_at(side.uv, t), f = outward_factors(side, t);
  Vec3 du, dv;
  side.surface->derivatives(P, c.x(), c.y(), du, dv);
  return f.x() * du + f.y() * dv;
}

TangentContinuityRows tangent_continuity_rows(const JointSide& first, const JointSide& second) {
  for (const JointSide* side : {&first, &second}) check_uv_curve(*side->surface, side->uv);
  // Integrate along the side with more multipliers, in its arc length; the other side is
  // evaluated at the same t.
  const bool first_leads = mortar_multiplier_count(*first.surface, first.uv) >= mortar_multiplier_count(*second.surface, second.uv);
  const JointSide& lead = first_leads ? first : second;
  const JointSide& other = first_leads ? second : first;
  const ArcLength arc(lead.uv), other_arc(other.uv);
  const double L = arc.length();
  std::vector<double> knots = mortar_knots(*lead.surface, lead.uv);
  const ClampedKnotBasis W = trace_multipliers(*lead.surface, lead.uv, L, knots);

  // Pieces on which both integrands are polynomials: either side's vertices and finest grid
  // lines (the other's mapped through t), and W's knots.
  std::vector<double> breaks = arc.S;
  breaks.insert(breaks.end(), knots.begin(), knots.end());
  for (std::size_t k = 0; k < other.uv.size(); ++k) breaks.push_back(arc.s_of(static_cast<double>(k) / (other.uv.size() - 1)));
  for (const JointSide* side : {&lead, &other}) {
    const ArcLength& a = side == &lead ? arc : other_arc;
    const double grid = std::ldexp(1.0, side->surface->level_count() - 1);
    for (std::size_t k = 0; k + 1 < side->uv.size(); ++k)
      for (int axis = 0; axis < 2; ++axis)
        grid_crossings(side->uv, a, k, axis, grid, [&](double sk, long long) { breaks.push_back(arc.s_of(a.t_of(sk))); });
  }
  std::sort(breaks.begin(), breaks.end());

  const int r = std::max(lead.surface->degree(), other.surface->degree());
  const GaussRule g = gauss_legendre((3 * r + 1) / 2 + 1);  // ψ (degree r) times a derivative trace (≤ 2r − 1)
  const int m = W.size();
  Triplets t_lead, t_other;
  Eigen::VectorXd mass = Eigen::VectorXd::Zero(m);
  BasisRow row;
  std::vector<double> psi;
  int first_psi = 0;
  const auto add = [&](const JointSide& side, double tq, const std::vector<double>& weights, Triplets& out) {
    const Eigen::Vector2d c = polyline_at(side.uv, tq), f = outward_factors(side, tq);
    side.surface->basis(c.x(), c.y(), row);
    for (std::size_t a = 0; a < weights.size(); ++a) {
      if (weights[a] == 0) continue;
      const int j = (first_psi + static_cast<int>(a)) % m;
      for (const BasisEntry& e : row) out.emplace_back(j, e.dof, weights[a] * (f.x() * e.du + f.y() * e.dv));
    }
  };
  std::vector<double> weights;
  for_each_gauss_point(breaks, L, g, [&](double sq, double w) {
    const double tq = arc.t_of(sq);
    W.evaluate(sq, first_psi, psi);
    weights.assign(psi.size(), 0.0);
    for (std::size_t a = 0; a < psi.size(); ++a) {
      weights[a] = w * psi[a];
      mass[(first_psi + static_cast<int>(a)) % m] += weights[a];
    }
    add(lead, tq, weights, t_lead);
    add(other, tq, weights, t_other);
  });
  const Eigen::VectorXd inverse_mass = mass.cwiseInverse();
  SparseMatrix A_lead(m, lead.surface->dof_count()), A_other(m, other.surface->dof_count());
  A_lead.setFromTriplets(t_lead.begin(), t_lead.end());
  A_other.setFromTriplets(t_other.begin(), t_other.end());
  TangentContinuityRows out;
  out.first = inverse_mass.asDiagonal() * (first_leads ? A_lead : A_other);
  out.second = inverse_mass.asDiagonal() * (first_leads ? A_other : A_lead);
  return out;
}

}  // namespace fairshape::bspline
