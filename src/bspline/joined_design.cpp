#include "fairshape/bspline/joined_design.h"

#include "fairshape/bspline/curve_fidelity.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "fairshape/bspline/mortar_curve.h"
#include "fairshape/core/error.h"
#include "fairshape/core/message_format.h"
#include "fairshape/core/timer.h"

namespace fairshape::bspline {

namespace {

// M's entries shifted to (row0, col0) of a larger matrix.
void place(Triplets& t, const SparseMatrix& M, Eigen::Index row0, Eigen::Index col0) {
  for (int k = 0; k < M.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(M, k); it; ++it)
      t.emplace_back(static_cast<int>(row0 + it.row()), static_cast<int>(col0 + it.col()), it.value());
}

void check_no_normals(const JoinedSheet& s) {
  for (const SheetConstraint& c : s.constraints)
    if (c.kind == SheetConstraint::Kind::Normal)
      throw InvalidInput((c.label.empty() ? std::string("normal constraint") : c.label) +
                         ": normal constraints are not supported on a sheet joined to a variational curve");
}

// One block of the joint program: its matrix rows at `column`, its targets.
struct RowBlock {
  std::vector<std::pair<const SparseMatrix*, Eigen::Index>> parts;  // (rows, column offset)
  Eigen::MatrixXd b;
};

}  // namespace

JoinedProgram assemble_joined(const JoinedDesign& design, Backend backend) {
  JoinedProgram out;
  const std::size_t S = design.sheets.size(), C = design.curves.size();
  std::vector<qp::QuadraticProgram> curve_programs;
  out.column.push_back(0);
  for (const JoinedSheet& s : design.sheets) {
    check_no_normals(s);
    out.sheet_programs.push_back(assemble(*s.sheet, s.energy, s.constraints, backend));
    out.column.push_back(out.column.back() + s.sheet->surface().dof_count());
  }
  for (const JoinedCurve& c : design.curves) {
    curve_programs.push_back(assemble(*c.curve, c.energy, c.constraints));
    out.column.push_back(out.column.back() + c.curve->dof_count());
  }
  std::vector<MortarRows> joints;
  std::vector<SparseMatrix> minus_B;
  for (const CurveJoint& j : design.joints) {
    FAIRSHAPE_ASSERT(j.sheet >= 0 && static_cast<std::size_t>(j.sheet) < S && j.curve >= 0 && static_cast<std::size_t>(j.curve) < C,
                     "a joint names a sheet and a curve of the design");
    try {
      // The multipliers on the finer side (bspline/mortar_curve.h): a curve finer than the
      // sheet's trace along the joint follows the sheet, a coarser one leads it.
      const HierarchicalSurface& surface = design.sheets[j.sheet].sheet->surface();
      const VariationalCurve& curve = *design.curves[j.curve].curve;
      const Multipliers side =
          curve.dof_count() > mortar_multiplier_count(surface, j.uv) ? Multipliers::Target : Multipliers::SurfaceTrace;
      joints.push_back(mortar_rows(surface, j.uv, curve.knot_basis(), side, &curve.basis().to_knot_basis()));
    } catch (const InvalidInput& e) {
      throw InvalidInput(j.label.empty() ? std::string(e.what()) : j.label + ": " + e.what());
    }
    minus_B.push_back(-joints.back().B);
  }

  // Row blocks: each member's own rows, then each joint's [A_sheet, −B_curve] with targets 0.
  std::vector<RowBlock> blocks;
  for (std::size_t k = 0; k < S; ++k) blocks.push_back({{{&out.sheet_programs[k].A, out.column[k]}}, out.sheet_programs[k].b});
  for (std::size_t k = 0; k < C; ++k) blocks.push_back({{{&curve_programs[k].A, out.column[S + k]}}, curve_programs[k].b});
  for (std::size_t k = 0; k < joints.size(); ++k) {
    const CurveJoint& j = design.joints[k];
    blocks.push_back({{{&joints[k].A, out.column[j.sheet]}, {&minus_B[k], out.column[S + j.curve]}},
                      Eigen::MatrixXd::Zero(joints[k].A.rows(), 3)});
  }
  // Tangent joints: [first rows at the first sheet, second rows at the second], targets 0.
  std::vector<TangentContinuityRows> tangents;
  for (const TangentJoint& tj : design.tangent_joints) {
    const std::string where = tj.label.empty() ? std::string("tangent continuity") : tj.label;
    const std::size_t J = design.joints.size();
    FAIRSHAPE_ASSERT(tj.first >= 0 && static_cast<std::size_t>(tj.first) < J && tj.second >= 0 && static_cast<std::size_t>(tj.second) < J,
                     "a tangent joint names two joints of the design");
    const CurveJoint &a = design.joints[tj.first], &b = design.joints[tj.second];
    if (a.curve != b.curve) throw InvalidInput(where + ": its two joints are on different curves");
    if (a.sheet == b.sheet) throw InvalidInput(where + ": its two joints are on the same sheet");
    const VariationalSheet &sa = *design.sheets[a.sheet].sheet, &sb = *design.sheets[b.sheet].sheet;
    const JointSide first{&sa.surface(), a.uv, tj.keep_left_first}, second{&sb.surface(), b.uv, tj.keep_left_second};
    try {
      tangents.push_back(tangent_continuity_rows(first, second));
    } catch (const InvalidInput& e) {
      throw InvalidInput(where + ": " + e.what());
    }
    // Crossing the curve must leave one kept side and enter the other: their outward directions
    // (across the curve, in space) point away from each other. Both kept sides on one side of
    // the curve (a wrong `keep`) would fold one sheet back over the other without a word.
    const VariationalCurve& X = *design.curves[a.curve].curve;
    double worst = -1;
    for (double t : {0.25, 0.5, 0.75}) {
      const Vec3 along = X.tangent(t).normalized();
      Vec3 o1 = outward_derivative(first, sa.coefficients(), t), o2 = outward_derivative(second, sb.coefficients(), t);
      o1 -= o1.dot(along) * along;
      o2 -= o2.dot(along) * along;
      if (o1.norm() == 0 || o2.norm() == 0) continue;
      worst = std::max(worst, o1.normalized().dot(o2.normalized()));
    }
    if (worst > 0.5)
      throw InvalidInput(where + ": the kept sides lie on the same side of the curve (their outward directions are " +
                         std::to_string(static_cast<int>(std::lround(std::acos(std::min(worst, 1.0)) * 180 / 3.141592653589793))) +
                         " degrees apart, expected near 180): swap one `keep` side");
  }
  for (std::size_t k = 0; k < tangents.size(); ++k) {
    const TangentJoint& tj = design.tangent_joints[k];
    blocks.push_back({{{&tangents[k].first, out.column[design.joints[tj.first].sheet]},
                       {&tangents[k].second, out.column[design.joints[tj.second].sheet]}},
                      Eigen::MatrixXd::Zero(tangents[k].first.rows(), 3)});
  }
  const Eigen::Index n = out.column.back();
  Triplets th, tk, ta;
  Eigen::Index k_rows = 0;
  qp::QuadraticProgram& p = out.program;
  p.f.resize(n, 3);
  const auto add_energy = [&](const qp::QuadraticProgram& member, Eigen::Index col) {
    place(th, member.H, col, col);
    place(tk, member.K, k_rows, col);
    k_rows += member.K.rows();
    p.f.middleRows(col, member.H.rows()) = member.f;
  };
  for (std::size_t k = 0; k < S; ++k) add_energy(out.sheet_programs[k], out.column[k]);
  for (std::size_t k = 0; k < C; ++k) add_energy(curve_programs[k], out.column[S + k]);
  out.row.push_back(0);
  for (const RowBlock& b : blocks) {
    for (const auto& [M, col] : b.parts) place(ta, *M, out.row.back(), col);
    out.row.push_back(out.row.back() + b.b.rows());
  }
  p.H.resize(n, n);
  p.H.setFromTriplets(th.begin(), th.end());
  p.K.resize(k_rows, n);
  p.K.setFromTriplets(tk.begin(), tk.end());
  p.A.resize(out.row.back(), n);
  p.A.setFromTriplets(ta.begin(), ta.end());
  p.b.resize(out.row.back(), 3);
  for (std::size_t k = 0; k < blocks.size(); ++k) p.b.middleRows(out.row[k], blocks[k].b.rows()) = blocks[k].b;
  return out;
}

double JoinedReport::max_error() const {
  double worst = 0;
  for (const auto& cells : sheet_errors) worst = std::max(worst, bspline::max_error(cells));
  for (const auto& leaves : curve_leaf_errors)
    for (double e : leaves) worst = std::max(worst, e);
  return worst;
}

double JoinedReport::energy() const {
  return std::accumulate(sheet_energy.begin(), sheet_energy.end(), 0.0) + std::accumulate(curve_energy.begin(), curve_energy.end(), 0.0);
}

namespace {

// |w(c(t)) − X(t)| at 2(r + 1) points of every leaf cell of the curve, the worst into its leaf.
void add_joint_errors(const VariationalSheet& sheet, const std::vector<Eigen::Vector2d>& uv, const VariationalCurve& X,
                      std::vector<double>& leaf_error) {
  const int samples = 2 * (X.basis().degree() + 1);
  const std::vector<CurveSpan>& leaves = X.basis().leaf_cells();
  for (std::size_t k = 0; k < leaves.size(); ++k)
    for (int i = 0; i <= samples; ++i) {
      const double t = leaves[k].t0 + (leaves[k].t1 - leaves[k].t0) * i / samples;
      const Eigen::Vector2d c = polyline_at(uv, t);
      const double e = (sheet.surface().position(sheet.coefficients(), c.x(), c.y()) - X.position(t)).norm();
      leaf_error[k] = std::max(leaf_error[k], e);
    }
}

// The errors, energies and per-member residuals of the design at the answer p.
void measure(const JoinedDesign& design, const JoinedProgram& jp, const Eigen::MatrixXd& p, JoinedReport& report) {
  const std::size_t S = design.sheets.size(), C = design.curves.size(), J = design.joints.size();
  const Eigen::MatrixXd residual = jp.program.A * p - jp.program.b;
  const auto block_norm = [&](std::size_t b) { return residual.middleRows(jp.row[b], jp.row[b + 1] - jp.row[b]).norm(); };
  report.sheet_energy.assign(S, 0.0);
  report.sheet_errors.assign(S, {});
  report.sheet_residual.assign(S, 0.0);
  for (std::size_t k = 0; k < S; ++k) {
    const JoinedSheet& s = design.sheets[k];
    report.sheet_energy[k] = objective_value(*s.sheet, s.energy, jp.sheet_programs[k]);
    report.sheet_residual[k] = block_norm(k);
    // Its own constraints against their polylines, its joints against the curves' X(t).
    std::vector<SheetConstraint> all = s.constraints;
    std::vector<const VariationalCurve*> joined_to(all.size(), nullptr);
    for (std::size_t j = 0; j < J; ++j) {
      if (design.joints[j].sheet != static_cast<int>(k)) continue;
      SheetConstraint c;
      c.kind = SheetConstraint::Kind::Curve;
      c.curve.uv = design.joints[j].uv;
      all.push_back(c);
      joined_to.push_back(design.curves[design.joints[j].curve].curve);
      report.sheet_residual[k] = std::hypot(report.sheet_residual[k], block_norm(S + C + j));
    }
    report.sheet_errors[k] = constraint_errors(*s.sheet, all, [&](std::size_t i, double t) {
      return joined_to[i] ? joined_to[i]->position(t) : curve_target_at(all[i].curve, t);
    });
  }
  for (std::size_t k = 0; k < C; ++k) {
    const JoinedCurve& c = design.curves[k];
    report.curve_energy.push_back(curve_energy(*c.curve, c.energy));
    report.curve_error.push_back(bspline::max_error(*c.curve, c.constraints));
    report.curve_residual.push_back(block_norm(S + k));
    report.curve_leaf_errors.push_back(leaf_errors(*c.curve, c.constraints));
  }
  for (std::size_t j = 0; j < J; ++j) {
    const CurveJoint& joint = design.joints[j];
    SheetConstraint c;
    c.kind = SheetConstraint::Kind::Curve;
    c.curve.uv = joint.uv;
    const VariationalCurve& X = *design.curves[joint.curve].curve;
    report.joint_error.push_back(
        bspline::max_error(constraint_errors(*design.sheets[joint.sheet].sheet, {c}, [&](std::size_t, double t) { return X.position(t); })));
    add_joint_errors(*design.sheets[joint.sheet].sheet, joint.uv, X, report.curve_leaf_errors[joint.curve]);
    const std::size_t b = S + C + j;
    report.joint_weak.push_back(residual.middleRows(jp.row[b], jp.row[b + 1] - jp.row[b]).cwiseAbs().maxCoeff());
  }
  for (std::size_t k = 0; k < design.tangent_joints.size(); ++k) {
    const TangentJoint& tj = design.tangent_joints[k];
    const CurveJoint &a = design.joints[tj.first], &b = design.joints[tj.second];
    const VariationalSheet &sa = *design.sheets[a.sheet].sheet, &sb = *design.sheets[b.sheet].sheet;
    const JointSide first{&sa.surface(), a.uv, tj.keep_left_first}, second{&sb.surface(), b.uv, tj.keep_left_second};
    double worst = 0;
    const int samples = 64 * std::max(sa.surface().level_count(), sb.surface().level_count());
    for (int i = 0; i <= samples; ++i) {
      const double t = static_cast<double>(i) / samples;
      worst = std::max(worst, (outward_derivative(first, sa.coefficients(), t) + outward_derivative(second, sb.coefficients(), t)).norm());
    }
    report.tangent_error.push_back(worst);
    const std::size_t block = S + C + J + k;
    report.tangent_weak.push_back(residual.middleRows(jp.row[block], jp.row[block + 1] - jp.row[block]).cwiseAbs().maxCoeff());
  }
}

}  // namespace

namespace {

JoinedReport solve_once(JoinedDesign& design, qp::QpSolver& solver, Backend backend) {
  JoinedReport report;
  const JoinedProgram jp = assemble_joined(design, backend);
  // The rows acting on each member: a sheet's own and its joints', a curve's own.
  const std::size_t S = design.sheets.size(), C = design.curves.size();
  const auto block_rows = [&](std::size_t b) { return static_cast<int>(jp.row[b + 1] - jp.row[b]); };
  for (std::size_t k = 0; k < S; ++k) report.sheet_rows.push_back(block_rows(k));
  for (std::size_t k = 0; k < C; ++k) report.curve_rows.push_back(block_rows(S + k));
  const std::size_t J = design.joints.size();
  for (std::size_t j = 0; j < J; ++j) report.sheet_rows[design.joints[j].sheet] += block_rows(S + C + j);
  for (std::size_t k = 0; k < design.tangent_joints.size(); ++k)  // they act on both sheets
    for (int joint : {design.tangent_joints[k].first, design.tangent_joints[k].second})
      report.sheet_rows[design.joints[joint].sheet] += block_rows(S + C + J + k);
  solver.analyze(jp.program);
  report.analyze_s = solver.analyze_seconds();
  const Timer timer;
  report.qp = solver.solve(jp.program.f, jp.program.b);
  report.solve_s = timer.seconds();
  report.message = report.qp.summary.message;
  const Termination t = report.qp.summary.termination;
  // As solve_sheet: an answer under constraints_unmet or ill_conditioned is kept and measured.
  const bool has_answer = t == Termination::Converged || t == Termination::ConstraintsUnmet || t == Termination::IllConditioned;
  if (!has_answer || !report.qp.p.allFinite()) return report;
  for (std::size_t k = 0; k < jp.column.size() - 1; ++k) {
    Eigen::MatrixXd part = report.qp.p.middleRows(jp.column[k], jp.column[k + 1] - jp.column[k]);
    if (k < S) design.sheets[k].sheet->set_coefficients(std::move(part));
    else design.curves[k - S].curve->set_control_points(std::move(part));
  }
  measure(design, jp, report.qp.p, report);
  return report;
}

// The curve's leaf cells whose error exceeds the tolerance and whose next layer is within max_level.
std::vector<CurveSpan> leaves_to_refine(const VariationalCurve& c, const std::vector<double>& errors, const RefinementOptions& refinement) {
  std::vector<CurveSpan> out;
  const std::vector<CurveSpan>& leaves = c.basis().leaf_cells();
  for (std::size_t k = 0; k < leaves.size(); ++k)
    if (errors[k] > refinement.tolerance && leaves[k].level + 1 <= refinement.max_level) out.push_back(leaves[k]);
  return out;
}

}  // namespace

namespace {
JoinedReport solve_and_refine(JoinedDesign& design, qp::QpSolver& solver, Backend backend, const RefinementOptions& refinement);

// A sheet's own fixed curve constraints judged as on a single sheet (bspline/curve_fidelity.h):
// a point of the sheet on one of them asking another position is a conflict between that
// sheet's own constraints, whatever the joints do; an unresolved one is a warning.
void check_sheet_curves(const JoinedDesign& design, const RefinementOptions& refinement, Backend backend, JoinedReport& report) {
  if (report.qp.summary.termination != Termination::Converged) return;
  const auto append = [&](const std::string& text) {
    report.message = (report.message.empty() ? "" : report.message + "; ") + text;
    report.qp.summary.message = report.message;
  };
  for (std::size_t k = 0; k < design.sheets.size(); ++k) {
    const JoinedSheet& s = design.sheets[k];
    if (const auto conflict = curve_conflict(*s.sheet, s.constraints, refinement.curve_conflict_tolerance)) {
      report.qp.summary.termination = Termination::ConstraintsUnmet;
      append(describe(*conflict, s.constraints, s.sheet->surface().shape().span_size));
      return;
    }
    if (const auto conflict = curve_slope_conflict(*s.sheet, s.constraints, refinement.curve_slope_tolerance)) {
      report.qp.summary.termination = Termination::ConstraintsUnmet;
      append(describe(*conflict, s.constraints, s.sheet->surface().shape().span_size));
      return;
    }
    if (refinement.curve_limit_share <= 0) continue;
    const CurveConvergence c = curve_convergence(*s.sheet, s.energy, s.constraints, backend, refinement.curve_error_factor,
                                                 refinement.curve_limit_share, refinement.curve_conflict_tolerance);
    report.sheet_curve_probe.resize(design.sheets.size());
    report.sheet_curve_probe[k] = c;
    if (!c.unresolved) continue;
    append(describe_unresolved(c, s.constraints));
    if (c.meeting) {
      report.qp.summary.termination = Termination::ConstraintsUnmet;
      return;
    }
  }
}
}  // namespace

JoinedReport solve_joined(JoinedDesign& design, qp::QpSolver& solver, Backend backend, const RefinementOptions& refinement) {
  JoinedReport report = solve_and_refine(design, solver, backend, refinement);
  check_sheet_curves(design, refinement, backend, report);
  return report;
}

namespace {
JoinedReport solve_and_refine(JoinedDesign& design, qp::QpSolver& solver, Backend backend, const RefinementOptions& refinement) {
  const std::size_t S = design.sheets.size(), C = design.curves.size();
  std::vector<int> sheet_refined(S, 0), curve_refined(C, 0);
  double analyze_s = 0, solve_s = 0;
  for (int round = 1;; ++round) {
    JoinedReport report = solve_once(design, solver, backend);
    analyze_s += report.analyze_s;
    solve_s += report.solve_s;
    report.analyze_s = analyze_s, report.solve_s = solve_s, report.rounds = round;
    report.sheet_spans_refined = sheet_refined, report.curve_spans_refined = curve_refined;
    const Termination t = report.qp.summary.termination;
    const bool measured = report.sheet_errors.size() == S && report.curve_leaf_errors.size() == C;
    if (refinement.tolerance <= 0 || !measured || (t != Termination::Converged && t != Termination::ConstraintsUnmet)) return report;
    const double worst = report.max_error();
    if (worst <= refinement.tolerance) return report;
    const auto unmet = [&](const std::string& why) {
      report.qp.summary.termination = Termination::ConstraintsUnmet;
      report.message = (report.message.empty() ? "" : report.message + "; ") + "constraint error " + sci(worst) +
                       " above the refinement tolerance " + sci(refinement.tolerance) + " " + why;
      report.qp.summary.message = report.message;
      return report;
    };
    if (round > refinement.max_rounds) return unmet("after " + std::to_string(refinement.max_rounds) + " refinement rounds");
    bool refined = false;
    for (std::size_t k = 0; k < S; ++k) {
      const std::vector<SpanId> spans = spans_to_refine(design.sheets[k].sheet->surface(), report.sheet_errors[k], refinement);
      if (!spans.empty()) sheet_refined[k] += design.sheets[k].sheet->refine(spans), refined = true;
    }
    for (std::size_t k = 0; k < C; ++k) {
      const std::vector<CurveSpan> leaves = leaves_to_refine(*design.curves[k].curve, report.curve_leaf_errors[k], refinement);
      if (!leaves.empty()) curve_refined[k] += design.curves[k].curve->refine(leaves), refined = true;
    }
    if (!refined) return unmet("at the maximum depth " + std::to_string(refinement.max_level));
  }
}
}  // namespace

}  // namespace fairshape::bspline
