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

// |w(c(t)) − D(t)| of constraint c at `samples` + 1 samples equally spaced in t.
Eigen::VectorXd error_profile(const HierarchicalSurface& s, const Eigen::MatrixXd& P, const SheetConstraint& c, int samples) {
  Eigen::VectorXd e(samples + 1);
  for (int k = 0; k <= samples; ++k) {
    const double t = static_cast<double>(k) / samples;
    const Eigen::Vector2d uv = polyline_at(c.curve.uv, t);
    e[k] = (s.position(P, uv.x(), uv.y()) - polyline_at(c.curve.space, t)).norm();
  }
  return e;
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

// The error profile constraint c leaves alone on the sheet (a vanishing ridge fixes what it
// leaves free, e.g. a turn about a straight curve); empty when that solve fails.
Eigen::VectorXd alone_profile(const VariationalSheet& sheet, const SheetEnergy& energy, const SheetConstraint& c, Backend backend,
                              int samples) {
  qp::QuadraticProgram alone = assemble(sheet, energy, {c}, backend);
  SparseMatrix ridge(alone.H.rows(), alone.H.cols());
  ridge.setIdentity();
  alone.H += 1e-10 * std::max(1.0, alone.H.diagonal().cwiseAbs().maxCoeff()) * ridge;
  const Eigen::MatrixXd P = direct_solve(alone, sheet, backend);
  if (P.size() == 0) return {};
  return error_profile(sheet.surface(), P, c, samples);
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

// The worst of `e` over each run of kPieceSamples samples: the error of each piece of the curve.
constexpr int kPieceSamples = 8;
Eigen::VectorXd piece_errors(const Eigen::VectorXd& e) {
  const Eigen::Index pieces = (e.size() + kPieceSamples - 1) / kPieceSamples;
  Eigen::VectorXd out(pieces);
  for (Eigen::Index p = 0; p < pieces; ++p)
    out[p] = e.segment(p * kPieceSamples, std::min<Eigen::Index>(kPieceSamples, e.size() - p * kPieceSamples)).maxCoeff();
  return out;
}

// The verdict on one curve constraint (see curve_convergence).
CurveConvergence judge_curve(const VariationalSheet& sheet, const SheetEnergy& energy, const std::vector<SheetConstraint>& constraints,
                             std::size_t index, Backend backend, double alone_factor, double limit_share, double tolerance) {
  const HierarchicalSurface& s = sheet.surface();
  const SheetConstraint& c = constraints[index];
  CurveConvergence out;
  out.constraint = static_cast<int>(index);
  // One sampling in t for every solve below, so pieces of the curve can be compared.
  const int samples = curve_samples(s, c.curve.uv);
  const Eigen::VectorXd error = piece_errors(error_profile(s, sheet.coefficients(), c, samples));
  out.error = error.maxCoeff();
  // An error below the tolerance is not a conflict worth the name (and rounding has nothing to
  // converge to).
  if (!(out.error > tolerance)) return out;
  // Compared piece by piece: a conflict shows where the other constraint acts, which need not
  // be where the curve's own error is largest (Figure 1 with a point 0.02 above the arc's
  // start: the worst error 0.030 is 1.4 times the worst alone, at the lifted middle).
  const Eigen::VectorXd alone_samples = alone_profile(sheet, energy, c, backend, samples);
  if (alone_samples.size() == 0) return out;  // the solve failed: not judged
  const Eigen::VectorXd alone = piece_errors(alone_samples);
  out.alone_error = alone.maxCoeff();
  const Eigen::Array<bool, Eigen::Dynamic, 1> suspect = error.array() > alone_factor * alone.array() && error.array() > tolerance;
  if (!suspect.any()) return out;
  // Twice, every span the curve crosses one level finer (a discretization error along the curve
  // is set by the cells on both sides of it all along, not by the worst sample's alone), and
  // each suspect piece's error extrapolated from the three: a conflict's stays where the other
  // constraint acts, a discretization error falls there (a sheet bent hard across the curve
  // converges slowly overall, but piece by piece).
  VariationalSheet finer = sheet;
  Eigen::VectorXd errors[3] = {error, {}, {}};
  for (int round = 1; round <= 2; ++round) {
    if (!refine_along(finer, c.curve.uv)) return out;
    const Eigen::MatrixXd P = direct_solve(assemble(finer, energy, constraints, backend), finer, backend);
    if (P.size() == 0) return out;
    finer.set_coefficients(P);
    errors[round] = piece_errors(error_profile(finer.surface(), finer.coefficients(), c, samples));
  }
  // The suspect piece whose limit is largest against what refinement left.
  double worst_share = -1;
  for (Eigen::Index p = 0; p < error.size(); ++p) {
    if (!suspect[p]) continue;
    const double limit = error_limit(errors[0][p], errors[1][p], errors[2][p]);
    const double share = limit / errors[2][p];
    if (!(share > worst_share)) continue;
    worst_share = share;
    out.excess_t = std::min(1.0, static_cast<double>(p * kPieceSamples) / samples);
    out.excess_error = errors[0][p];
    out.excess_alone_error = alone[p];
    out.refined_error = errors[1][p];
    out.twice_refined_error = errors[2][p];
    out.limit = limit;
    out.conflict = limit > limit_share * errors[2][p] && limit > tolerance;
    if (out.conflict) break;
  }
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
