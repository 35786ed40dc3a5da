// Welch & Witkin's modelling session (§5) as a library object: sheets with their constraints,
// their objectives and one constrained solver kept across steps, advanced one design step at a
// time — a constraint installed, dragged or removed, the rest shape installed or melted, the
// sheet refined by constraint error (§4.4). Each step solves the sheets something acts on and
// measures its result on them (the constraint errors per leaf cell, each constraint's own error,
// the conflict checks of curve_fidelity.h), so every front end — a config run, Python, an
// editor — gets the same checks.
//
// The solver's factorization is reused across steps whose program keeps its rows and energy (a
// drag: new targets only; qp/kkt_solver.h, qp/qr_penalty_solver.h), and each sheet keeps its
// thin-plate H until it is refined (VariationalSheet::thin_plate), so a drag step costs a solve
// and the checks (papers/welch-witkin/README.md, "A drag step and its checks").
#pragma once

#include <algorithm>
#include <cstddef>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fairshape/bspline/variational_sheet.h"
#include "fairshape/core/summary.h"
#include "fairshape/qp/qp_solver.h"

namespace fairshape {

//! A constraint of the session: numbered 0, 1, 2, … in the order the session makes them (or
//! given by the caller: a config run numbers them as its `constraints:` list).
using SheetHandle = int;

struct SheetSessionOptions {
  bspline::SheetEnergy energy;          // every sheet's objective at the start (eq. 4 or 6)
  bspline::RefinementOptions refinement;  // tolerance 0: a step does not refine
  Backend backend = Backend::Optimized;
};

//! What a step measures beyond the solve. The curve resolution probe (curve_fidelity.h) costs
//! several solves per curve: an editor leaves it off while dragging and asks for it on release.
struct SheetChecks {
  bool curve_probe = true;
};

//! §5's actions on a sheet's objective, at the start of a step: install its current shape as
//! its rest shape (eq. 6 about it from then on), or melt the rest shape (eq. 4 again).
struct RestShapeChange {
  enum class Kind { Install, Melt } kind = Kind::Install;
  std::optional<std::size_t> sheet;  // none: every sheet
};

//! A constraint as the session holds it: on which sheet, and what it asks.
struct SessionConstraint {
  std::size_t sheet = 0;
  bspline::SheetConstraint constraint;
};

//! The changes of one design step, applied in this order before its solve: rest-shape actions,
//! removals, then constraints put (added, or replacing what a handle asked).
struct SheetEdits {
  std::vector<RestShapeChange> rest;
  std::vector<SheetHandle> remove;
  std::vector<std::pair<SheetHandle, SessionConstraint>> put;  // handle −1: a new one, numbered next
};

//! Sheets solved with something outside the session (a variational curve they are joined to,
//! bspline/joined_design.h): what such a solve gives each of its sheets.
struct JointSheetReport {
  bspline::DesignReport report;
  std::string factorization;
};
//! Called after a step's edits with every sheet, its objective and its own active constraints
//! (handle order); solves the joined sheets in place and returns their reports by sheet index.
//! The session solves the others.
using JointSolve = std::function<std::map<std::size_t, JointSheetReport>(
    std::vector<bspline::VariationalSheet>&, const std::vector<bspline::SheetEnergy>&,
    const std::vector<std::vector<bspline::SheetConstraint>>&)>;

//! One constraint measured on the sheet after the step: a point's or offset's distance from what
//! it asked (both given), a curve's or region's largest |w − D| over its samples (§4.4's measure);
//! a tangent's or normal's is not measured per constraint (NaN: its rows' residual is the
//! solve's constraint_residual, its agreement with crossing curves the slope-conflict check).
struct SheetConstraintCheck {
  SheetHandle handle = -1;
  double error = std::numeric_limits<double>::quiet_NaN();
  Vec3 asked = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  Vec3 achieved = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
};

//! One sheet's solve in a step.
struct SheetSolve {
  std::size_t sheet = 0;
  bool joint = false;          // solved by the JointSolve with a variational curve
  bspline::DesignReport report;
  std::string factorization;   // how the program was factored (qp::factorization_note)
  Eigen::MatrixXd coefficients;  // the sheet's control points after the step (a copy)
};

//! What one step did and achieved.
struct SheetStep {
  //! Converged, or the first failing sheet's termination with "sheet NAME: why".
  SolveSummary summary;
  std::vector<SheetHandle> added;  // handles the step made (put with −1), in order
  std::vector<SheetSolve> sheets;  // every sheet solved, in sheet order (none when nothing acts)
  std::vector<SheetConstraintCheck> checks;  // every active constraint of a solved sheet, handle order
  double max_constraint_error = 0;  // over the solved sheets' leaf cells
  double energy = 0;                // summed over the solved sheets
  double solve_s = 0;  // factorizations and solves
  //! The rest of the step: the program's assembly, the errors per cell, the conflict checks, the
  //! probe and the per-constraint checks.
  double check_s = 0;
  bool solved_any() const { return !sheets.empty(); }
};

class SheetSession {
 public:
  //! Sheets with their names (for messages), as they start; `solver` is kept across steps.
  SheetSession(std::vector<std::string> names, std::vector<bspline::VariationalSheet> sheets, SheetSessionOptions options,
               std::unique_ptr<qp::QpSolver> solver);
  SheetSession(const SheetSession&) = delete;  // owns the solver and its factorization
  SheetSession& operator=(const SheetSession&) = delete;
  SheetSession(SheetSession&&) = default;
  SheetSession& operator=(SheetSession&&) = default;

  // The paper's steps, each one solve. \throw InvalidInput for an unknown handle or sheet, or a
  // constraint the sheet cannot hold (outside its domain, ...): nothing changes then.
  SheetStep add(SessionConstraint c, const SheetChecks& checks = {});
  //! A drag: a point's target, an offset, a region's shift, a tangent's vector, a normal.
  SheetStep move(SheetHandle h, const Vec3& target, const SheetChecks& checks = {});
  //! A curve constraint's space curve moved (its samples; the traced surface it keeps).
  SheetStep move_curve(SheetHandle h, std::vector<Vec3> space, const SheetChecks& checks = {});
  SheetStep remove(SheetHandle h, const SheetChecks& checks = {});
  SheetStep install_rest_shape(std::optional<std::size_t> sheet = std::nullopt, const SheetChecks& checks = {});
  SheetStep melt(std::optional<std::size_t> sheet = std::nullopt, const SheetChecks& checks = {});
  //! §4.4: solve again refining every cell whose constraint error is above `tolerance` (the
  //! session's refinement options otherwise), as deep as they allow.
  SheetStep refine(double tolerance, const SheetChecks& checks = {});
  //! Several changes, one solve (a config's design step). `joints` solves the joined sheets.
  SheetStep apply(const SheetEdits& edits, const SheetChecks& checks = {}, const JointSolve& joints = {});

  //! §4.4's a-posteriori estimate (every cell refined once, solved again): expensive, on request.
  bspline::ObjectiveErrorEstimate estimate_objective_error(std::size_t sheet);

  const std::vector<bspline::VariationalSheet>& sheets() const { return sheets_; }
  const bspline::VariationalSheet& sheet(std::size_t k) const;
  const std::vector<std::string>& names() const { return names_; }
  std::size_t sheet_index(const std::string& name) const;  // \throw InvalidInput naming the sheets
  //! The sheets as they started (relative targets and displacement are measured from them).
  const bspline::HierarchicalSurface& initial_surface(std::size_t k) const { return initial_surfaces_.at(k); }
  const Eigen::MatrixXd& initial_coefficients(std::size_t k) const { return initial_P_.at(k); }
  //! The sheet as it is now, kept as a target surface (a curve traced on it, a region or
  //! ribbon holding it).
  std::shared_ptr<const bspline::SurfaceTrace> surface_now(std::size_t k) const;
  const std::map<SheetHandle, SessionConstraint>& constraints() const { return constraints_; }
  const SessionConstraint& constraint(SheetHandle h) const;
  //! Handles below n are the caller's to give (a config numbers its constraints by their place
  //! in its list): the session numbers the constraints it makes from n on.
  void reserve_handles(SheetHandle n) { next_handle_ = std::max(next_handle_, n); }
  //! Sheet k's constraints, in handle order.
  std::vector<bspline::SheetConstraint> active(std::size_t k) const;
  const bspline::SheetEnergy& energy(std::size_t k) const { return energies_.at(k); }
  const SheetSessionOptions& options() const { return options_; }
  qp::QpSolver& solver() { return *solver_; }

 private:
  void apply_rest_shape(const RestShapeChange& r);
  SheetSolve solve_one(std::size_t k, const std::vector<bspline::SheetConstraint>& active, const SheetChecks& checks,
                       double& check_s);
  void measure(SheetStep& step) const;

  std::vector<std::string> names_;
  std::vector<bspline::VariationalSheet> sheets_;
  std::vector<bspline::HierarchicalSurface> initial_surfaces_;
  std::vector<Eigen::MatrixXd> initial_P_;
  std::vector<bspline::SheetEnergy> energies_;
  SheetSessionOptions options_;
  std::unique_ptr<qp::QpSolver> solver_;
  std::map<SheetHandle, SessionConstraint> constraints_;
  SheetHandle next_handle_ = 0;
};

}  // namespace fairshape
