// Sheets joined along variational curves, solved as one program. Welch &
// Witkin ("Variational surface modeling", §5) join two sheets "by snapping a pair of surface
// curves to a single space curve", and make curves first-class variational objects; here the
// space curve is a VariationalCurve whose control points are unknowns beside the sheets':
//   unknowns  [p_sheet1; p_sheet2; ...; q_curve1; ...]   (n × 3, x, y, z sharing every row)
//   energy    Σ each sheet's objective (eq. 4 or 6, or the displacement metric) + Σ each
//             curve's own energy: H block-diagonal
//   rows      every sheet's and every curve's own constraints (zero blocks elsewhere), and per
//             joint the mortar rows of bspline/mortar_curve.h with the curve as target,
//             ∫ψ_j (w(c(s)) − X(t(s))) ds / ∫ψ_j = 0:   [ … A_sheet … −B_curve … ] = 0
// Any registered QP solver takes the program; its constraint policy reports unmet or
// ill-posed rows as for a single sheet. Normal constraints (which stack a sheet's x, y and z)
// are refused on joined sheets. Automatic refinement (§4.4) refines, after each solve, the
// sheet cells and the curve's leaf cells where a constraint or a joint misses by more than the
// tolerance — both sides of a joint, since either may be the one too coarse to follow.
#pragma once

#include "fairshape/bspline/curve_fidelity.h"

#include <string>
#include <vector>

#include "fairshape/bspline/variational_curve.h"
#include "fairshape/bspline/variational_sheet.h"

namespace fairshape::bspline {

//! w_sheet(c(t)) = X_curve(t), weakly: the sheet's (u, v) polyline (base-span units, points
//! equally spaced in t) paired with the curve by t ∈ [0, 1].
struct CurveJoint {
  int sheet = 0, curve = 0;  // indices into JoinedDesign::sheets and ::curves
  std::vector<Eigen::Vector2d> uv;
  std::string label;  // for messages: "constraints[0]"
};

//! Two joints of one curve made tangent-continuous (bspline/mortar_curve.h,
//! tangent_continuity_rows): the sides of their (u, v) curves each sheet keeps.
struct TangentJoint {
  int first = 0, second = 0;  // indices into JoinedDesign::joints, on the same curve
  bool keep_left_first = true, keep_left_second = false;
  std::string label;
};

struct JoinedSheet {
  VariationalSheet* sheet = nullptr;
  SheetEnergy energy;
  std::vector<SheetConstraint> constraints;  // its own (no normals)
};

struct JoinedCurve {
  VariationalCurve* curve = nullptr;
  CurveEnergy energy;
  std::vector<CurveConstraint> constraints;
};

struct JoinedDesign {
  std::vector<JoinedSheet> sheets;
  std::vector<JoinedCurve> curves;
  std::vector<CurveJoint> joints;
  std::vector<TangentJoint> tangent_joints;
};

//! The joint program and where each member sits in it: member k (the sheets, then the curves)
//! owns columns [column[k], column[k + 1]); row block b (each sheet's own rows, each curve's
//! own rows, each joint's, then each tangent joint's) owns rows [row[b], row[b + 1]).
struct JoinedProgram {
  qp::QuadraticProgram program;
  std::vector<qp::QuadraticProgram> sheet_programs;  // each sheet's own (its energy's H and f)
  std::vector<Eigen::Index> column, row;
};
//! \throw InvalidInput naming the constraint's label: a normal constraint on a joined sheet, a
//! joint's (u, v) outside its sheet, a bad curve constraint, a tangent joint between joints of
//! different curves or of one sheet.
JoinedProgram assemble_joined(const JoinedDesign& design, Backend backend);

struct JoinedReport {
  qp::QpReport qp;
  double analyze_s = 0, solve_s = 0;
  std::vector<double> sheet_energy, curve_energy;     // each member's objective
  //! Per sheet, per leaf cell: its own constraints' errors and |w(c(t)) − X(t)| along its joints.
  std::vector<std::vector<CellError>> sheet_errors;
  std::vector<double> curve_error;                    // per curve: its own constraints
  //! Per curve, per leaf cell: its own constraints' errors and |w(c(t)) − X(t)| of its joints.
  std::vector<std::vector<double>> curve_leaf_errors;
  std::vector<double> joint_error;                    // per joint: max |w(c(t)) − X(t)| sampled (pointwise)
  std::vector<double> joint_weak;                     // per joint: max |row residual| (the weak form, a distance)
  //! Per tangent joint: max |∂w₁/∂n₁ + ∂w₂/∂n₂| sampled (pointwise) and its rows' max |residual|.
  std::vector<double> tangent_error, tangent_weak;
  std::vector<int> sheet_rows, curve_rows;            // a sheet's own rows and its joints'; a curve's own
  std::vector<double> sheet_residual, curve_residual;  // ‖A p − b‖_F over those rows
  int rounds = 0;                                      // solves (1 + refinements)
  std::vector<int> sheet_spans_refined, curve_spans_refined;
  //! Per sheet: the probe of its own weak curve constraints (curve_fidelity.h; default-constructed
  //! where it did not run), for steps.csv's curve_error columns.
  std::vector<CurveConvergence> sheet_curve_probe;
  std::string message;
  double energy() const;
  //! The largest error of any sheet cell or curve leaf: what refinement compares with its tolerance.
  double max_error() const;
};

//! Solves the joint program and hands each sheet its coefficients and each curve its control
//! points (when the solver returns an answer: converged, constraints_unmet or ill_conditioned;
//! a failed factorization leaves every member as it was, and the report has its row counts
//! but no energies or errors). With a refinement tolerance, refines and solves again while an
//! error exceeds it (an unmet answer included: a finer member may meet what a coarse one could
//! not); an error still above it after max_rounds or at max_level is constraints_unmet, saying so.
JoinedReport solve_joined(JoinedDesign& design, qp::QpSolver& solver, Backend backend, const RefinementOptions& refinement = {});

}  // namespace fairshape::bspline
