#include "fairshape/bspline/curve_fidelity.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "fairshape/bspline/surface_constraints.h"
#include "fairshape/core/message_format.h"
#include "fairshape/qp/kkt_solver.h"

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
    e[k] = (s.position(P, uv.x(), uv.y()) - curve_target_at(c.curve, t)).norm();
  }
  return e;
}

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

// Every span the uv polyline crosses or passes within one leaf cell of, one level finer; false
// when all are at the deepest layer. The band makes the refinement blind to how the path meets
// cell corners (a diagonal through them: the cells on one side only, so a legal point just off
// the path on the other side kept its error and looked like a conflict, while its mirror image
// did not).
bool refine_along(VariationalSheet& sheet, const std::vector<Eigen::Vector2d>& uv) {
  const HierarchicalSurface& s = sheet.surface();
  const double U = s.shape().spans_u, V = s.shape().spans_v;
  std::vector<SpanId> spans;
  const auto add = [&](double u, double v) {
    if (s.shape().periodic_u) u = u - U * std::floor(u / U);
    else if (u < 0 || u > U) return;
    if (v < 0 || v > V) return;
    const SpanId cell = s.leaf_cell_at(u, v);
    const SpanId span = s.has_span(cell) ? cell : SpanId{cell.level - 1, cell.i / 2, cell.j / 2};
    if (span.level + 1 > HierarchicalSurface::kMaxLevel) return;
    if (std::none_of(spans.begin(), spans.end(), [&](const SpanId& o) { return o.level == span.level && o.i == span.i && o.j == span.j; }))
      spans.push_back(span);
  };
  const int samples = curve_samples(s, uv);
  for (int k = 0; k <= samples; ++k) {
    const Eigen::Vector2d at = polyline_at(uv, static_cast<double>(k) / samples);
    const double h = std::ldexp(1.0, -s.leaf_cell_at(at.x(), at.y()).level);  // the leaf cell's size there
    for (int du = -1; du <= 1; ++du)
      for (int dv = -1; dv <= 1; ++dv) add(at.x() + du * h, at.y() + dv * h);
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

// The pieces of a curve: runs of kPieceSamples of the `samples` + 1 samples the judged sheet
// takes, as intervals of t. A refined sheet samples more densely (curve_samples grows with its
// levels), so a conflict's spike, which narrows with the cells, stays sampled; each piece's
// error is the worst of the samples in its interval, whatever their number.
constexpr int kPieceSamples = 8;
Eigen::VectorXd piece_errors(const Eigen::VectorXd& e, int piece_samples) {
  const std::int64_t dense = e.size() - 1;
  const Eigen::Index pieces = piece_samples / kPieceSamples + 1;
  Eigen::VectorXd out = Eigen::VectorXd::Zero(pieces);
  for (std::int64_t k = 0; k <= dense; ++k) {
    const Eigen::Index p = static_cast<Eigen::Index>(k * piece_samples / (dense * kPieceSamples));
    out[p] = std::max(out[p], e[k]);
  }
  return out;
}

// The verdict on one curve constraint (see curve_convergence).
CurveConvergence judge_curve(const VariationalSheet& sheet, const SheetEnergy& energy, const std::vector<SheetConstraint>& constraints,
                             std::size_t index, const std::vector<Coincidence>& meetings, Backend backend, double alone_factor,
                             double limit_share, double tolerance) {
  const HierarchicalSurface& s = sheet.surface();
  const SheetConstraint& c = constraints[index];
  CurveConvergence out;
  out.constraint = static_cast<int>(index);
  // The pieces of this sheet's sampling: every solve below is judged on the same intervals of t.
  const int samples = curve_samples(s, c.curve.uv);
  const Eigen::VectorXd error = piece_errors(error_profile(s, sheet.coefficients(), c, samples), samples);
  out.error = error.maxCoeff();
  // An error below the tolerance is not a conflict worth the name (and rounding has nothing to
  // converge to).
  if (!(out.error > tolerance)) return out;
  // Compared piece by piece: a conflict shows where the other constraint acts, which need not
  // be where the curve's own error is largest (Figure 1 with a point 0.02 above the arc's
  // start: the worst error 0.030 is 1.4 times the worst alone, at the lifted middle).
  const Eigen::VectorXd alone_samples = alone_profile(sheet, energy, c, backend, samples);
  if (alone_samples.size() == 0) return out;  // the solve failed: not judged
  const Eigen::VectorXd alone = piece_errors(alone_samples, samples);
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
    errors[round] = piece_errors(error_profile(finer.surface(), finer.coefficients(), c, curve_samples(finer.surface(), c.curve.uv)),
                                 samples);
  }
  // Every suspect piece is judged. Reported: an unresolved piece next to a constraint meeting
  // the curve (within two pieces), else an unresolved one, each with the largest limit; else
  // the piece whose limit is largest.
  const double piece_t = static_cast<double>(kPieceSamples) / samples;
  const auto rank = [](bool unresolved, bool met) { return (unresolved ? 2 : 0) + (met ? 1 : 0); };
  double reported_limit = -1;
  for (Eigen::Index p = 0; p < error.size(); ++p) {
    if (!suspect[p]) continue;
    const double limit = error_limit(errors[0][p], errors[1][p], errors[2][p]);
    const bool unresolved = limit > limit_share * errors[2][p] && limit > tolerance;
    const double middle = (static_cast<double>(p) + 0.5) * piece_t;
    std::optional<Coincidence> met;
    if (unresolved)
      for (const Coincidence& m : meetings)
        if (std::abs(m.t - middle) <= 2 * piece_t && (!met || std::abs(m.t - middle) < std::abs(met->t - middle))) met = m;
    const int r = rank(unresolved, met.has_value()), reported = rank(out.unresolved, out.meeting.has_value());
    if (r < reported || (r == reported && !(limit > reported_limit))) continue;
    reported_limit = limit;
    out.excess_t = std::min(1.0, static_cast<double>(p) * piece_t);
    out.excess_error = errors[0][p];
    out.excess_alone_error = alone[p];
    out.refined_error = errors[1][p];
    out.twice_refined_error = errors[2][p];
    out.limit = limit;
    out.unresolved = unresolved;
    out.meeting = met;
  }
  return out;
}

// "On the path": within a millionth of the parameter domain (typed coordinates with six digits;
// a point farther off is beside the path, where the continuous problem is consistent).
double on_path_distance(const VariationalSheet& sheet) {
  return 1e-6 * std::max(sheet.surface().shape().spans_u, sheet.surface().shape().spans_v);
}
}  // namespace

std::optional<Coincidence> curve_conflict(const VariationalSheet& sheet, const std::vector<SheetConstraint>& constraints,
                                          double conflict_tolerance) {
  return conflicting_coincidence(constraints, on_path_distance(sheet), conflict_tolerance * surface_size(sheet));
}

std::optional<SlopeMismatch> curve_slope_conflict(const VariationalSheet& sheet, const std::vector<SheetConstraint>& constraints,
                                                  double slope_tolerance) {
  return slope_conflict(constraints, sheet.surface().shape().span_size, on_path_distance(sheet), slope_tolerance);
}

CurveConvergence curve_convergence(const VariationalSheet& sheet, const SheetEnergy& energy,
                                   const std::vector<SheetConstraint>& constraints, Backend backend, double alone_factor,
                                   double limit_share, double conflict_tolerance) {
  const double tolerance = conflict_tolerance * surface_size(sheet);
  // Every curve on its own: one with a large error of its own must not hide another's.
  const std::vector<Coincidence> all_meetings = coincidences(constraints, on_path_distance(sheet));
  CurveConvergence worst;
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    if (!judged(constraints[i])) continue;
    std::vector<Coincidence> meetings;
    for (const Coincidence& m : all_meetings)
      if (m.curve == static_cast<int>(i)) meetings.push_back(m);
    const CurveConvergence c = judge_curve(sheet, energy, constraints, i, meetings, backend, alone_factor, limit_share, tolerance);
    if (c.unresolved) return c;
    if (worst.constraint < 0 || c.error > worst.error) worst = c;
  }
  return worst;
}

std::string describe_unresolved(const CurveConvergence& c, const std::vector<SheetConstraint>& constraints) {
  const std::string& label = constraints[static_cast<std::size_t>(c.constraint)].label;
  const std::string curve = label.empty() ? std::string("a curve constraint") : label;
  if (c.meeting) {
    const std::string& other = constraints[static_cast<std::size_t>(c.meeting->other)].label;
    return curve + ": its pointwise error " + sci(c.excess_error) + " at t = " + sci(c.excess_t) + " (" +
           sci(c.excess_error / c.excess_alone_error) + " times its error alone there) stays under refinement along it (" +
           sci(c.refined_error) + ", " + sci(c.twice_refined_error) + ", tending to " + sci(c.limit) + ") where " +
           (other.empty() ? std::string("another constraint") : other) + " meets it (t = " + sci(c.meeting->t) +
           ", the same position asked): the two ask slopes no surface has there";
  }
  return "warning: " + curve +
         " is not resolved at this resolution: its pointwise error " + sci(c.excess_error) + " at t = " + sci(c.excess_t) + " (" +
         sci(c.excess_error / c.excess_alone_error) + " times its error alone there) stays under refinement along it (" +
         sci(c.refined_error) + ", " + sci(c.twice_refined_error) + ", tending to " + sci(c.limit) +
         "); no constraint on its path asks another position, so a constraint beside it asks a steep surface (refine: "
         "refinement.tolerance) — or a tangent or normal on its path contradicts it (not compared exactly)";
}

}  // namespace fairshape::bspline
