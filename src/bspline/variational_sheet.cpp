#include "fairshape/bspline/variational_sheet.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <tuple>

#include "fairshape/bspline/curve_fidelity.h"
#include "fairshape/bspline/mortar_curve.h"
#include "fairshape/bspline/region_constraint.h"
#include "fairshape/bspline/ribbon_constraint.h"
#include "fairshape/core/error.h"
#include "fairshape/core/message_format.h"
#include "fairshape/core/timer.h"
#include "fairshape/problem/constrained_system.h"
#include "fairshape/qp/qr_penalty_solver.h"

namespace fairshape::bspline {

VariationalSheet::VariationalSheet(const SheetShape& shape, Eigen::MatrixXd initial) : surface_(shape) {
  if (initial.rows() != surface_.dof_count() || initial.cols() != 3)
    throw InvalidInput("initial control points: expected " + std::to_string(surface_.dof_count()) + " x 3");
  P_ = std::move(initial);
  rest_ = remembered_ = P_;
}

VariationalSheet::VariationalSheet(HierarchicalSurface surface, Eigen::MatrixXd P, Eigen::MatrixXd rest)
    : surface_(std::move(surface)) {
  const int n = surface_.dof_count();
  if (P.rows() != n || P.cols() != 3 || rest.rows() != n || rest.cols() != 3)
    throw InvalidInput("sheet control points: expected " + std::to_string(n) + " x 3 (current and rest)");
  P_ = std::move(P);
  rest_ = remembered_ = std::move(rest);
}

void VariationalSheet::set_coefficients(Eigen::MatrixXd P) {
  FAIRSHAPE_ASSERT(P.rows() == surface_.dof_count() && P.cols() == 3, "coefficients do not match the surface");
  P_ = std::move(P);
}

int VariationalSheet::refine(const std::vector<SpanId>& spans) {
  std::size_t before = 0;
  for (int l = 0; l < surface_.level_count(); ++l) before += surface_.span_count(l);
  // Coarser layers first: a list may name spans that an earlier entry's refinement creates.
  std::map<int, std::vector<SpanId>> by_level;
  for (const SpanId& s : spans) by_level[s.level].push_back(s);
  for (const auto& [level, group] : by_level) {
    const SparseMatrix T = surface_.refine(group);
    P_ = T * P_;
    rest_ = T * rest_;
    remembered_ = T * remembered_;
  }
  std::size_t after = 0;
  for (int l = 0; l < surface_.level_count(); ++l) after += surface_.span_count(l);
  if (after != before) thin_plate_.reset();
  return static_cast<int>(after - before);
}

const VariationalSheet::ThinPlate& VariationalSheet::thin_plate(const TensionWeights& weights, Backend backend) const {
  const bool same = thin_plate_ && thin_plate_->backend == backend && thin_plate_->weights.alpha == weights.alpha &&
                    thin_plate_->weights.beta == weights.beta && thin_plate_->H.rows() == surface_.dof_count();
  if (!same) {
    auto fresh = std::make_shared<ThinPlate>();
    fresh->weights = weights;
    fresh->backend = backend;
    fresh->H = thin_plate_hessian(surface_, weights, backend);
    thin_plate_ = std::move(fresh);
  }
  return *thin_plate_;
}

const SparseMatrix& VariationalSheet::thin_plate_square_root(const TensionWeights& weights, Backend backend) const {
  const ThinPlate& plate = thin_plate(weights, backend);
  if (!plate.K) plate.K = std::make_shared<const SparseMatrix>(bspline::thin_plate_square_root(surface_, weights));
  return *plate.K;
}

namespace {
// A program over the stacked unknowns [x; y; z] (rows coupling the coordinates) or over the
// control points' n × 3 coordinates (x, y and z sharing H and A).
bool is_stacked(const qp::QuadraticProgram& program, const VariationalSheet& sheet) {
  return program.hessian().rows() == 3 * static_cast<Eigen::Index>(sheet.surface().dof_count());
}
Eigen::MatrixXd in_program_shape(const Eigen::MatrixXd& P, bool stacked) {
  return stacked ? Eigen::MatrixXd(Eigen::Map<const Eigen::VectorXd>(P.data(), P.size())) : P;
}
Eigen::MatrixXd as_coefficients(const Eigen::MatrixXd& p, int dofs) {
  return p.cols() == 3 ? p : Eigen::MatrixXd(Eigen::Map<const Eigen::MatrixXd>(p.data(), dofs, 3));
}

// The program of the stacked unknowns: every per-coordinate row applies to x, y and z alike
// (kron(I₃, A)), the coupled rows (normals) act on all three at once.
void stack_coordinates(qp::QuadraticProgram& p, const ConstraintRows& shared, const std::vector<CoupledRows>& coupled) {
  p.H = block_diagonal(p.H, 3);
  if (p.K.size()) p.K = block_diagonal(p.K, 3);
  p.f = in_program_shape(p.f, true);
  std::vector<CoupledRows> parts{stacked(shared)};
  parts.insert(parts.end(), coupled.begin(), coupled.end());
  std::vector<const SparseMatrix*> blocks;
  Eigen::Index m = 0;
  for (const CoupledRows& c : parts) blocks.push_back(&c.A), m += c.b.size();
  p.A = stack_rows(blocks);
  p.b.resize(m, 1);
  m = 0;
  for (const CoupledRows& c : parts) p.b.middleRows(m, c.b.size()) = c.b, m += c.b.size();
}
}  // namespace

double objective_value(const VariationalSheet& sheet, const SheetEnergy& energy, const qp::QuadraticProgram& program) {
  const bool about_rest = energy.rest_shape || energy.metric == ShapeMetric::Displacement;
  const bool stacked = is_stacked(program, sheet);
  const Eigen::MatrixXd rest = in_program_shape(sheet.rest(), stacked);
  return qp::objective(program, in_program_shape(sheet.coefficients(), stacked)) +
         (about_rest ? 0.5 * (rest.transpose() * (program.hessian() * rest)).trace() : 0.0);
}

namespace {
// assemble(), and with borrow_H the program lends the sheet's cached H (QuadraticProgram::
// borrowed_H) instead of copying it, unless a coupled row stacks the coordinates: solve_sheet's
// programs live only while the sheet keeps its surface (README, "Memory of deep refinement").
qp::QuadraticProgram assemble_program(const VariationalSheet& sheet, const SheetEnergy& energy,
                                      const std::vector<SheetConstraint>& constraints, Backend backend, bool square_root,
                                      bool borrow_H) {
  const HierarchicalSurface& s = sheet.surface();
  qp::QuadraticProgram p;
  if (energy.metric == ShapeMetric::Displacement) {
    p.H.resize(s.dof_count(), s.dof_count());
    p.H.setIdentity();
    p.K = p.H;
    p.f = sheet.rest();
  } else {
    const VariationalSheet::ThinPlate& plate = sheet.thin_plate(energy.weights, backend);
    const bool coupled_rows = std::any_of(constraints.begin(), constraints.end(),
                                          [](const SheetConstraint& c) { return c.kind == SheetConstraint::Kind::Normal; });
    if (borrow_H && !coupled_rows) p.borrowed_H = &plate.H;
    else p.H = plate.H;
    if (square_root) p.K = sheet.thin_plate_square_root(energy.weights, backend);
    p.f = energy.rest_shape ? Eigen::MatrixXd(plate.H * sheet.rest()) : Eigen::MatrixXd::Zero(s.dof_count(), 3);
  }
  std::vector<ConstraintRows> rows;
  std::vector<CoupledRows> coupled;
  for (const SheetConstraint& c : constraints) {
    try {
      switch (c.kind) {
        case SheetConstraint::Kind::Point: rows.push_back(point_rows(s, c.u, c.v, c.target)); break;
        case SheetConstraint::Kind::Tangent: rows.push_back(tangent_rows(s, c.u, c.v, c.direction, c.target)); break;
        case SheetConstraint::Kind::Normal: coupled.push_back(normal_rows(s, c.u, c.v, c.target)); break;
        case SheetConstraint::Kind::Curve:
          rows.push_back(c.formulation == CurveFormulation::Mortar ? mortar_curve_rows(s, c.curve) : curve_rows(s, c.curve, c.quadrature));
          if (c.ribbon) rows.push_back(cross_tangent_rows(s, c.curve.uv, c.cross, c.surface.get()));
          break;
        case SheetConstraint::Kind::Offset: rows.push_back(offset_rows(s, {c.u, c.v}, c.other, c.target)); break;
        case SheetConstraint::Kind::Region:
          FAIRSHAPE_ASSERT(c.surface != nullptr, "a region constraint needs its target surface");
          rows.push_back(region_rows(s, {c.u, c.v}, c.other, *c.surface, c.target));
          break;
      }
    } catch (const InvalidInput& e) {
      throw InvalidInput(c.label.empty() ? std::string(e.what()) : c.label + ": " + e.what());
    }
  }
  const ConstraintRows all = stack(rows, s.dof_count());
  if (!coupled.empty()) {
    stack_coordinates(p, all, coupled);
    return p;
  }
  p.A = all.A;
  p.b = all.C;
  return p;
}
}  // namespace

qp::QuadraticProgram assemble(const VariationalSheet& sheet, const SheetEnergy& energy,
                              const std::vector<SheetConstraint>& constraints, Backend backend, bool square_root) {
  return assemble_program(sheet, energy, constraints, backend, square_root, /*borrow_H=*/false);
}

namespace {
struct CellKey {
  bool operator()(const SpanId& a, const SpanId& b) const {
    return std::tie(a.level, a.i, a.j) < std::tie(b.level, b.i, b.j);
  }
};
}  // namespace

std::vector<CellError> constraint_errors(const VariationalSheet& sheet, const std::vector<SheetConstraint>& constraints) {
  return constraint_errors(sheet, constraints, [&](std::size_t i, double t) { return curve_target_at(constraints[i].curve, t); });
}

std::vector<CellError> constraint_errors(const VariationalSheet& sheet, const std::vector<SheetConstraint>& constraints,
                                         const CurveTarget& target) {
  const HierarchicalSurface& s = sheet.surface();
  const Eigen::MatrixXd& P = sheet.coefficients();
  std::map<SpanId, double, CellKey> worst;
  const auto record = [&](double u, double v, double e) {
    double& w = worst[s.leaf_cell_at(u, v)];
    w = std::max(w, e);
  };
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    const SheetConstraint& c = constraints[i];
    if (c.kind == SheetConstraint::Kind::Point) record(c.u, c.v, (s.position(P, c.u, c.v) - c.target).norm());
    if (c.kind == SheetConstraint::Kind::Offset) {  // the relation's error, at both its points
      const double e = (s.position(P, c.u, c.v) - s.position(P, c.other.x(), c.other.y()) - c.target).norm();
      record(c.u, c.v, e);
      record(c.other.x(), c.other.y(), e);
    }
    if (c.kind == SheetConstraint::Kind::Region)  // |w − W| on a grid in every finest cell of R
      for_each_region_sample(s, {c.u, c.v}, c.other, 4, [&](double u, double v) {
        record(u, v, (s.position(P, u, v) - c.surface->surface.position(c.surface->P, u, v) - c.target).norm());
      });
    // A ribbon's cross-tangent error is a slope, not a distance: the per-cell errors (which drive
    // refinement) measure its position only (papers/welch-witkin/README.md, "Offsets, ribbons
    // and regions").
    if (c.kind != SheetConstraint::Kind::Curve) continue;
    // Samples dense enough to see every finest cell the curve crosses several times.
    const int samples = curve_samples(s, c.curve.uv);
    for (int k = 0; k <= samples; ++k) {
      const double t = static_cast<double>(k) / samples;
      const Eigen::Vector2d uv = polyline_at(c.curve.uv, t);
      record(uv.x(), uv.y(), (s.position(P, uv.x(), uv.y()) - target(i, t)).norm());
    }
  }
  std::vector<CellError> out;  // every leaf cell, 0 where no constraint acts
  for (const SpanId& cell : s.leaf_cells()) {
    const auto it = worst.find(cell);
    out.push_back({cell, it == worst.end() ? 0.0 : it->second});
  }
  return out;
}

double max_error(const std::vector<CellError>& errors) {
  double m = 0;
  for (const CellError& e : errors) m = std::max(m, e.error);
  return m;
}

std::vector<SpanId> spans_to_refine(const HierarchicalSurface& s, const std::vector<CellError>& errors, const RefinementOptions& refinement) {
  // The layer span holding each offending cell (a cell outside Ω_L is refined through its
  // parent span), once each.
  std::vector<SpanId> spans;
  std::set<SpanId, CellKey> seen;
  for (const CellError& e : errors) {
    if (e.error <= refinement.tolerance) continue;
    const SpanId span = s.has_span(e.cell) ? e.cell : SpanId{e.cell.level - 1, e.cell.i / 2, e.cell.j / 2};
    if (span.level + 1 > refinement.max_level) continue;
    if (seen.insert(span).second) spans.push_back(span);
  }
  return spans;
}

namespace {
// A weak curve constraint met row by row can still be held off its curve by another constraint
// (bspline/curve_fidelity.h).
void check_curve_convergence(const VariationalSheet& sheet, const SheetEnergy& energy, const std::vector<SheetConstraint>& constraints,
                             const RefinementOptions& options, Backend backend, DesignReport& report) {
  const Eigen::Vector2d& span_size = sheet.surface().shape().span_size;
  if (const auto conflict = curve_conflict(sheet, constraints, options.curve_conflict_tolerance)) {
    report.qp.summary.termination = Termination::ConstraintsUnmet;
    report.message = describe(*conflict, constraints, span_size) + " (tolerance: refinement.curve_conflict_tolerance " +
                     sci(options.curve_conflict_tolerance) + " of the sheet's size)";
    return;
  }
  if (const auto conflict = curve_slope_conflict(sheet, constraints, options.curve_slope_tolerance)) {
    report.qp.summary.termination = Termination::ConstraintsUnmet;
    report.message = describe(*conflict, constraints, span_size) + " (tolerance: refinement.curve_slope_tolerance " +
                     sci(options.curve_slope_tolerance) + ")";
    return;
  }
  if (options.curve_limit_share <= 0 || !options.curve_probe) return;
  // A curve met to the requested refinement tolerance is what was asked.
  if (options.tolerance > 0 && report.max_constraint_error <= options.tolerance) return;
  const CurveConvergence c =
      curve_convergence(sheet, energy, constraints, backend, options.curve_error_factor, options.curve_limit_share,
                        options.curve_conflict_tolerance);
  report.curve_error = c.error;
  report.curve_alone_error = c.alone_error;
  report.curve_error_refined = c.refined_error;
  report.curve_error_limit = c.limit;
  if (!c.unresolved) return;
  // With a constraint meeting the curve there, slopes that disagree; without, the continuous
  // problem is consistent and the discrete surface is not near the curve yet (a warning).
  if (c.meeting) report.qp.summary.termination = Termination::ConstraintsUnmet;
  report.message = (report.message.empty() ? "" : report.message + "; ") + describe_unresolved(c, constraints);
}
}  // namespace

DesignReport solve_sheet(VariationalSheet& sheet, const SheetEnergy& energy, const std::vector<SheetConstraint>& constraints,
                         qp::QpSolver& solver, const RefinementOptions& refinement, Backend backend) {
  DesignReport report;
  for (;;) {
    // K only for the solver that factors it (README, "Memory of deep refinement").
    const bool square_root = dynamic_cast<const qp::QrPenaltySolver*>(&solver) != nullptr;
    // H lent, not copied: the program ends with this round, before any refinement.
    const qp::QuadraticProgram program = assemble_program(sheet, energy, constraints, backend, square_root, /*borrow_H=*/true);
    solver.analyze(program);
    report.analyze_s += solver.analyze_seconds();
    const Timer timer;
    report.qp = solver.solve(program.f, program.b);
    report.solve_s += timer.seconds();
    ++report.rounds;
    report.constraint_rows = program.A.rows();
    const Termination t = report.qp.summary.termination;
    // Constraints unmet or ill-posed: the answer is kept and measured (the run reports what it
    // achieved under that termination); a failed factorization leaves the sheet as it was.
    const bool has_answer = t == Termination::Converged || t == Termination::ConstraintsUnmet || t == Termination::IllConditioned;
    if (has_answer && report.qp.p.allFinite()) {
      sheet.set_coefficients(as_coefficients(report.qp.p, sheet.surface().dof_count()));
      report.energy = objective_value(sheet, energy, program);
      report.errors_per_round.push_back(constraint_errors(sheet, constraints));
      report.max_constraint_error = max_error(report.errors_per_round.back());
    }
    if (t != Termination::Converged) {
      report.message = report.qp.summary.message;
      return report;
    }
    if (refinement.tolerance <= 0 || report.max_constraint_error <= refinement.tolerance) break;
    // A tolerance refinement cannot reach is not met: constraints_unmet, with what was achieved.
    if (report.rounds > refinement.max_rounds) {
      report.qp.summary.termination = Termination::ConstraintsUnmet;
      report.message = "constraint error " + sci(report.max_constraint_error) + " above the refinement tolerance " +
                       sci(refinement.tolerance) + " after " + std::to_string(refinement.max_rounds) + " rounds";
      break;
    }
    const std::vector<SpanId> spans = spans_to_refine(sheet.surface(), report.errors_per_round.back(), refinement);
    if (spans.empty()) {
      report.qp.summary.termination = Termination::ConstraintsUnmet;
      report.message = "constraint error " + sci(report.max_constraint_error) + " above the refinement tolerance " +
                       sci(refinement.tolerance) + " at the maximum depth " + std::to_string(refinement.max_level);
      break;
    }
    if (!report.unrefined) report.unrefined = std::make_shared<const VariationalSheet>(sheet);
    report.spans_refined += sheet.refine(spans);
  }
  // Point derivative constraints have no continuum limit (H² in two variables does not bound a
  // derivative at a point): refined around them the energy keeps falling and the surface turns
  // sharper there, so a refined answer is a resolution's, not the problem's.
  const bool point_derivatives = std::any_of(constraints.begin(), constraints.end(), [](const SheetConstraint& c) {
    return c.kind == SheetConstraint::Kind::Tangent || c.kind == SheetConstraint::Kind::Normal;
  });
  if (report.spans_refined > 0 && point_derivatives)
    report.message += std::string(report.message.empty() ? "" : "; ") +
                      "refined under a point tangent or normal constraint, which has no continuum limit: the energy keeps "
                      "falling with refinement (papers/welch-witkin/README.md)";
  if (report.qp.summary.termination == Termination::Converged) check_curve_convergence(sheet, energy, constraints, refinement, backend, report);
  if (!report.qp.summary.message.empty()) report.message = report.message.empty() ? report.qp.summary.message : report.qp.summary.message + "; " + report.message;
  return report;
}

ObjectiveErrorEstimate estimate_objective_error(const VariationalSheet& sheet, const SheetEnergy& energy,
                                                const std::vector<SheetConstraint>& constraints, qp::QpSolver& solver,
                                                Backend backend) {
  ObjectiveErrorEstimate out;
  const double energy_now = objective_value(sheet, energy, assemble(sheet, energy, constraints, backend));
  VariationalSheet finer = sheet;
  std::vector<SpanId> spans;
  std::set<SpanId, CellKey> seen;
  for (const SpanId& c : sheet.surface().leaf_cells()) {
    const SpanId span = sheet.surface().has_span(c) ? c : SpanId{c.level - 1, c.i / 2, c.j / 2};
    if (span.level + 1 <= HierarchicalSurface::kMaxLevel && seen.insert(span).second) spans.push_back(span);
  }
  finer.refine(spans);
  const DesignReport r = solve_sheet(finer, energy, constraints, solver, {}, backend);
  out.finer_dofs = finer.surface().dof_count();
  if (r.qp.summary.termination != Termination::Converged) {
    out.message = "objective error estimate: the finer solve failed: " + r.message;
    return out;
  }
  out.energy_change = std::abs(energy_now - r.energy) / std::max(std::abs(r.energy), 1e-300);
  const auto& shape = sheet.surface().shape();
  const int n = 32;
  for (int a = 0; a <= n; ++a)
    for (int b = 0; b <= n; ++b) {
      const double u = shape.spans_u * static_cast<double>(a) / n, v = shape.spans_v * static_cast<double>(b) / n;
      out.surface_change = std::max(out.surface_change, (sheet.surface().position(sheet.coefficients(), u, v) -
                                                         finer.surface().position(finer.coefficients(), u, v)).norm());
    }
  return out;
}

}  // namespace fairshape::bspline
