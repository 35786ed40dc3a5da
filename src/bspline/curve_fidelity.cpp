#include "bspline/curve_fidelity.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bspline/surface_constraints.h"
#include "qp/kkt_solver.h"

namespace fairshape::bspline {

int curve_samples(const HierarchicalSurface& s, const std::vector<Eigen::Vector2d>& uv) {
  double length = 0;
  for (std::size_t k = 0; k + 1 < uv.size(); ++k) length += (uv[k + 1] - uv[k]).norm();
  return std::max(64, static_cast<int>(8 * length * std::ldexp(1.0, s.level_count())));
}

namespace {
bool judged(const SheetConstraint& c) { return c.kind == SheetConstraint::Kind::Curve && c.formulation == CurveFormulation::Mortar; }

// The largest |w(c(t)) − D(t)| of constraint c over `samples` + 1 samples equally spaced in t.
double worst_error(const HierarchicalSurface& s, const Eigen::MatrixXd& P, const SheetConstraint& c, int samples) {
  double worst = 0;
  for (int k = 0; k <= samples; ++k) {
    const double t = static_cast<double>(k) / samples;
    const Eigen::Vector2d uv = polyline_at(c.curve.uv, t);
    worst = std::max(worst, (s.position(P, uv.x(), uv.y()) - polyline_at(c.curve.space, t)).norm());
  }
  return worst;
}
}  // namespace

namespace {
// Solves `program` for `sheet`'s surface with a direct KKT solve; the coefficients, or empty
// when the solve gave nothing finite.
Eigen::MatrixXd direct_solve(const qp::QuadraticProgram& program, const VariationalSheet& sheet, Backend backend) {
  qp::KktSolver solver(backend);
  solver.analyze(program);
  const qp::QpReport r = solver.solve(program.f, program.b);
  if (!r.p.allFinite() || r.p.size() == 0) return {};
  const int n = sheet.surface().dof_count();
  return r.p.cols() == 3 ? r.p : Eigen::MatrixXd(Eigen::Map<const Eigen::MatrixXd>(r.p.data(), n, 3));
}

// The error constraint c leaves alone on the sheet (a vanishing ridge fixes what it leaves
// free, e.g. a turn about a straight curve); NaN when that solve fails.
double alone_error(const VariationalSheet& sheet, const SheetEnergy& energy, const SheetConstraint& c, Backend backend) {
  qp::QuadraticProgram alone = assemble(sheet, energy, {c}, backend);
  SparseMatrix ridge(alone.H.rows(), alone.H.cols());
  ridge.setIdentity();
  alone.H += 1e-10 * std::max(1.0, alone.H.diagonal().cwiseAbs().maxCoeff()) * ridge;
  const Eigen::MatrixXd P = direct_solve(alone, sheet, backend);
  if (P.size() == 0) return std::numeric_limits<double>::quiet_NaN();
  return worst_error(sheet.surface(), P, c, curve_samples(sheet.surface(), c.curve.uv));
}

// Every span the uv polyline crosses, one level finer; false when all are at the deepest layer.
bool refine_along(VariationalSheet& sheet, const std::vector<Eigen::Vector2d>& uv) {
  const HierarchicalSurface& s = sheet.surface();
  std::vector<SpanId> spans;
  const int samples = curve_samples(s, uv);
  for (int k = 0; k <= samples; ++k) {
    const Eigen::Vector2d at = polyline_at(uv, static_cast<double>(k) / samples);
    const SpanId cell = s.leaf_cell_at(at.x(), at.y());
    const SpanId span = s.has_span(cell) ? cell : SpanId{cell.level - 1, cell.i / 2, cell.j / 2};
    if (span.level + 1 > HierarchicalSurface::kMaxLevel) continue;
    if (std::none_of(spans.begin(), spans.end(), [&](const SpanId& o) { return o.level == span.level && o.i == span.i && o.j == span.j; }))
      spans.push_back(span);
  }
  if (spans.empty()) return false;
  sheet.refine(spans);
  return true;
}

// L of e_k = L + C q^k through three errors (Aitken's Δ²). An error that does not fall at each
// refinement has shown no convergence and is its own limit; one that falls faster and faster
// (d2 ≥ d1 > 0: a refinement resolving what the coarser one could not) is taken to fall at least
// once more by as much.
double error_limit(double e0, double e1, double e2) {
  const double d1 = e0 - e1, d2 = e1 - e2;
  if (!(d1 > 0) || !(d2 > 0)) return e2;
  if (!(d1 > d2)) return std::max(0.0, e2 - d2);
  const double q = d2 / d1;
  return std::max(0.0, e2 - d2 * q / (1 - q));
}

// The surface's extent: the diagonal of its points on a grid over the domain (its control
// points can lie far outside it: ±23,000 for a degree-5 sheet whose surface spans 2.5).
double surface_size(const VariationalSheet& sheet) {
  const HierarchicalSurface& s = sheet.surface();
  const int n = 16;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double u = s.shape().spans_u * (s.shape().periodic_u ? static_cast<double>(i) / (n + 1) : static_cast<double>(i) / n);
      const Vec3 x = s.position(sheet.coefficients(), u, s.shape().spans_v * static_cast<double>(j) / n);
      lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
    }
  return (hi - lo).norm();
}

// The verdict on one curve constraint (see curve_convergence).
CurveConvergence judge_curve(const VariationalSheet& sheet, const SheetEnergy& energy, const std::vector<SheetConstraint>& constraints,
                             std::size_t index, Backend backend, double alone_factor, double limit_share, double tolerance) {
  const HierarchicalSurface& s = sheet.surface();
  const SheetConstraint& c = constraints[index];
  CurveConvergence out;
  out.constraint = static_cast<int>(index);
  out.error = worst_error(s, sheet.coefficients(), c, curve_samples(s, c.curve.uv));
  // An error below the tolerance is not a conflict worth the name (and rounding has nothing to
  // converge to).
  if (!(out.error > tolerance)) return out;
  out.alone_error = alone_error(sheet, energy, c, backend);
  if (!(out.error > alone_factor * out.alone_error)) return out;  // NaN: not judged
  // Twice, every span the curve crosses one level finer (a discretization error along the curve
  // is set by the cells on both sides of it all along, not by the worst sample's alone), and
  // the error's limit extrapolated from the three.
  VariationalSheet finer = sheet;
  double errors[3] = {out.error, 0, 0};
  for (int round = 1; round <= 2; ++round) {
    if (!refine_along(finer, c.curve.uv)) return out;
    const Eigen::MatrixXd P = direct_solve(assemble(finer, energy, constraints, backend), finer, backend);
    if (P.size() == 0) return out;
    finer.set_coefficients(P);
    errors[round] = worst_error(finer.surface(), finer.coefficients(), c, curve_samples(finer.surface(), c.curve.uv));
  }
  out.refined_error = errors[1];
  out.twice_refined_error = errors[2];
  out.limit = error_limit(errors[0], errors[1], errors[2]);
  out.conflict = out.limit > limit_share * errors[2] && out.limit > tolerance;
  return out;
}
}  // namespace

CurveConvergence curve_convergence(const VariationalSheet& sheet, const SheetEnergy& energy,
                                   const std::vector<SheetConstraint>& constraints, Backend backend, double alone_factor,
                                   double limit_share, double conflict_tolerance) {
  // Every curve on its own: one with a large error of its own must not hide another's conflict.
  const double tolerance = conflict_tolerance * surface_size(sheet);
  CurveConvergence worst;
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    if (!judged(constraints[i])) continue;
    const CurveConvergence c = judge_curve(sheet, energy, constraints, i, backend, alone_factor, limit_share, tolerance);
    if (c.conflict) return c;
    if (worst.constraint < 0 || c.error > worst.error) worst = c;
  }
  return worst;
}

}  // namespace fairshape::bspline
