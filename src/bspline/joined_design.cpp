#include "bspline/joined_design.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "bspline/mortar_curve.h"
#include "core/error.h"
#include "core/timer.h"

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
      const ClampedKnotBasis& basis = design.curves[j.curve].curve->basis();
      const Multipliers side = basis.size() > mortar_multiplier_count(surface, j.uv) ? Multipliers::Target : Multipliers::SurfaceTrace;
      joints.push_back(mortar_rows(surface, j.uv, basis, side));
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

double JoinedReport::energy() const {
  return std::accumulate(sheet_energy.begin(), sheet_energy.end(), 0.0) + std::accumulate(curve_energy.begin(), curve_energy.end(), 0.0);
}

namespace {

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
      return joined_to[i] ? joined_to[i]->position(t) : polyline_at(all[i].curve.space, t);
    });
  }
  for (std::size_t k = 0; k < C; ++k) {
    const JoinedCurve& c = design.curves[k];
    report.curve_energy.push_back(curve_energy(*c.curve, c.energy));
    report.curve_error.push_back(max_error(*c.curve, c.constraints));
    report.curve_residual.push_back(block_norm(S + k));
  }
  for (std::size_t j = 0; j < J; ++j) {
    const CurveJoint& joint = design.joints[j];
    SheetConstraint c;
    c.kind = SheetConstraint::Kind::Curve;
    c.curve.uv = joint.uv;
    const VariationalCurve& X = *design.curves[joint.curve].curve;
    report.joint_error.push_back(
        max_error(constraint_errors(*design.sheets[joint.sheet].sheet, {c}, [&](std::size_t, double t) { return X.position(t); })));
    const std::size_t b = S + C + j;
    report.joint_weak.push_back(residual.middleRows(jp.row[b], jp.row[b + 1] - jp.row[b]).cwiseAbs().maxCoeff());
  }
}

}  // namespace

JoinedReport solve_joined(JoinedDesign& design, qp::QpSolver& solver, Backend backend) {
  JoinedReport report;
  const JoinedProgram jp = assemble_joined(design, backend);
  // The rows acting on each member: a sheet's own and its joints', a curve's own.
  const std::size_t S = design.sheets.size(), C = design.curves.size();
  const auto block_rows = [&](std::size_t b) { return static_cast<int>(jp.row[b + 1] - jp.row[b]); };
  for (std::size_t k = 0; k < S; ++k) report.sheet_rows.push_back(block_rows(k));
  for (std::size_t k = 0; k < C; ++k) report.curve_rows.push_back(block_rows(S + k));
  for (std::size_t j = 0; j < design.joints.size(); ++j) report.sheet_rows[design.joints[j].sheet] += block_rows(S + C + j);
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

}  // namespace fairshape::bspline
