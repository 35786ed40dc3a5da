#include "fairshape/bspline/sheet_session.h"

#include <algorithm>
#include <sstream>

#include "fairshape/core/error.h"
#include "fairshape/core/timer.h"
#include "fairshape/qp/range_space_solver.h"

namespace fairshape {

using bspline::SheetConstraint;

namespace {

// The constraint's (u, v) points, every one inside the sheet's domain (in base spans).
void check_in_domain(const bspline::HierarchicalSurface& s, const SheetConstraint& c, const std::string& what) {
  std::vector<Eigen::Vector2d> at;
  if (c.kind == SheetConstraint::Kind::Curve) at = c.curve.uv;
  else at.emplace_back(c.u, c.v);
  if (c.kind == SheetConstraint::Kind::Offset || c.kind == SheetConstraint::Kind::Region) at.push_back(c.other);
  if (c.kind == SheetConstraint::Kind::Curve && at.size() < 2) throw InvalidInput(what + ": a curve needs at least two (u, v) points");
  for (const Eigen::Vector2d& p : at)
    if (!s.in_domain(p.x(), p.y())) {
      std::ostringstream m;
      m << what << ": (u, v) = (" << p.x() << ", " << p.y() << ") base spans is outside the sheet's domain";
      throw InvalidInput(m.str());
    }
}

std::string handle_name(SheetHandle h) {
  std::ostringstream m;
  m << "constraint " << h;
  return m.str();
}

}  // namespace

SheetSession::SheetSession(std::vector<std::string> names, std::vector<bspline::VariationalSheet> sheets,
                           SheetSessionOptions options, std::unique_ptr<qp::QpSolver> solver)
    : names_(std::move(names)), sheets_(std::move(sheets)), options_(std::move(options)), solver_(std::move(solver)) {
  if (names_.size() != sheets_.size()) throw InvalidInput("SheetSession: one name per sheet");
  if (sheets_.empty()) throw InvalidInput("SheetSession: at least one sheet");
  if (!solver_) throw InvalidInput("SheetSession: no solver");
  for (const bspline::VariationalSheet& s : sheets_) {
    initial_surfaces_.push_back(s.surface());
    initial_P_.push_back(s.coefficients());
  }
  energies_.assign(sheets_.size(), options_.energy);
}

const bspline::VariationalSheet& SheetSession::sheet(std::size_t k) const {
  if (k >= sheets_.size()) throw InvalidInput("SheetSession: no sheet " + std::to_string(k) + " (" + std::to_string(sheets_.size()) + " sheets)");
  return sheets_[k];
}

std::size_t SheetSession::sheet_index(const std::string& name) const {
  for (std::size_t k = 0; k < names_.size(); ++k)
    if (names_[k] == name) return k;
  std::string all;
  for (const std::string& n : names_) all += (all.empty() ? "" : ", ") + n;
  throw InvalidInput("no sheet named '" + name + "' (sheets: " + all + ")");
}

std::shared_ptr<const bspline::SurfaceTrace> SheetSession::surface_now(std::size_t k) const {
  const bspline::VariationalSheet& s = sheet(k);
  return std::make_shared<const bspline::SurfaceTrace>(bspline::SurfaceTrace{s.surface(), s.coefficients()});
}

const SessionConstraint& SheetSession::constraint(SheetHandle h) const {
  const auto it = constraints_.find(h);
  if (it == constraints_.end()) throw InvalidInput("SheetSession: no " + handle_name(h) + " (removed, or never made)");
  return it->second;
}

std::vector<SheetConstraint> SheetSession::active(std::size_t k) const {
  std::vector<SheetConstraint> out;
  for (const auto& [h, c] : constraints_)
    if (c.sheet == k) out.push_back(c.constraint);
  return out;
}

SheetStep SheetSession::add(SessionConstraint c, const SheetChecks& checks) {
  SheetEdits e;
  e.put.emplace_back(-1, std::move(c));
  return apply(e, checks);
}

SheetStep SheetSession::move(SheetHandle h, const Vec3& target, const SheetChecks& checks) {
  SessionConstraint c = constraint(h);
  if (c.constraint.kind == SheetConstraint::Kind::Curve)
    throw InvalidInput("SheetSession::move: " + handle_name(h) + " is a curve: move its space curve (move_curve)");
  c.constraint.target = target;
  SheetEdits e;
  e.put.emplace_back(h, std::move(c));
  return apply(e, checks);
}

SheetStep SheetSession::move_curve(SheetHandle h, std::vector<Vec3> space, const SheetChecks& checks) {
  SessionConstraint c = constraint(h);
  if (c.constraint.kind != SheetConstraint::Kind::Curve)
    throw InvalidInput("SheetSession::move_curve: " + handle_name(h) + " is not a curve constraint (move its target)");
  c.constraint.curve.space = std::move(space);
  SheetEdits e;
  e.put.emplace_back(h, std::move(c));
  return apply(e, checks);
}

SheetStep SheetSession::remove(SheetHandle h, const SheetChecks& checks) {
  SheetEdits e;
  e.remove.push_back(h);
  return apply(e, checks);
}

SheetStep SheetSession::install_rest_shape(std::optional<std::size_t> sheet, const SheetChecks& checks) {
  SheetEdits e;
  e.rest.push_back({RestShapeChange::Kind::Install, sheet});
  return apply(e, checks);
}

SheetStep SheetSession::melt(std::optional<std::size_t> sheet, const SheetChecks& checks) {
  SheetEdits e;
  e.rest.push_back({RestShapeChange::Kind::Melt, sheet});
  return apply(e, checks);
}

SheetStep SheetSession::refine(double tolerance, const SheetChecks& checks) {
  if (!(tolerance > 0)) throw InvalidInput("SheetSession::refine: the tolerance must be positive");
  const double kept = options_.refinement.tolerance;
  options_.refinement.tolerance = tolerance;
  try {
    SheetStep s = apply({}, checks);
    options_.refinement.tolerance = kept;
    return s;
  } catch (...) {
    options_.refinement.tolerance = kept;
    throw;
  }
}

void SheetSession::apply_rest_shape(const RestShapeChange& r) {
  if (r.sheet) (void)sheet(*r.sheet);
  for (std::size_t k = 0; k < sheets_.size(); ++k) {
    if (r.sheet && *r.sheet != k) continue;
    if (r.kind == RestShapeChange::Kind::Install) sheets_[k].install_rest_shape();
    // Melting goes back to eq. 4 (the paper's "melt": the rest shape no longer pulls).
    energies_[k].rest_shape = r.kind == RestShapeChange::Kind::Install;
  }
}

SheetStep SheetSession::apply(const SheetEdits& edits, const SheetChecks& checks, const JointSolve& joints) {
  // Checked before anything changes, so a refused step leaves the session as it was.
  for (const SheetHandle h : edits.remove) (void)constraint(h);
  for (const auto& [h, c] : edits.put) {
    const std::string what = h < 0 ? "the new constraint" : handle_name(h);
    check_in_domain(sheet(c.sheet).surface(), c.constraint, what);
  }
  for (const RestShapeChange& r : edits.rest)
    if (r.sheet) (void)sheet(*r.sheet);
  const auto kept_constraints = constraints_;
  const auto kept_energies = energies_;
  const SheetHandle kept_next = next_handle_;
  SheetStep step;
  try {
    for (const RestShapeChange& r : edits.rest) apply_rest_shape(r);
    for (const SheetHandle h : edits.remove) constraints_.erase(h);
    for (const auto& [h, c] : edits.put) {
      const SheetHandle id = h < 0 ? next_handle_ : h;
      if (h < 0) step.added.push_back(id);
      constraints_[id] = c;
      next_handle_ = std::max(next_handle_, id + 1);
    }
    std::vector<std::vector<SheetConstraint>> actives(sheets_.size());
    for (std::size_t k = 0; k < sheets_.size(); ++k) actives[k] = active(k);
    std::map<std::size_t, JointSheetReport> joined;
    if (joints) joined = joints(sheets_, energies_, actives);
    bool failed = false;
    step.summary.termination = Termination::Converged;
    for (std::size_t k = 0; k < sheets_.size(); ++k) {
      const auto joint = joined.find(k);
      if (actives[k].empty() && joint == joined.end()) continue;  // nothing acts on it: it keeps its shape
      // After a failure only the sheets solved with the failed group are still reported (they
      // share its answer); nothing else is solved.
      if (failed && joint == joined.end()) continue;
      SheetSolve s;
      if (joint != joined.end()) {
        s.sheet = k, s.joint = true, s.report = joint->second.report, s.factorization = joint->second.factorization;
        s.coefficients = sheets_[k].coefficients();
      } else {
        s = solve_one(k, actives[k], checks, step.check_s);
      }
      step.solve_s += s.report.analyze_s + s.report.solve_s;
      const bool this_failed = !is_success(s.report.qp.summary.termination);
      if (this_failed && !failed) {
        step.summary.termination = s.report.qp.summary.termination;
        step.summary.message = "sheet " + names_[k] + ": " + s.report.message;
      }
      failed = failed || this_failed;
      step.sheets.push_back(std::move(s));
    }
  } catch (...) {
    constraints_ = kept_constraints;
    energies_ = kept_energies;
    next_handle_ = kept_next;
    throw;
  }
  const Timer timer;
  measure(step);
  step.check_s += timer.seconds();
  return step;
}

SheetSolve SheetSession::solve_one(std::size_t k, const std::vector<SheetConstraint>& active, const SheetChecks& checks,
                                   double& check_s) {
  bspline::RefinementOptions refinement = options_.refinement;
  refinement.curve_probe = checks.curve_probe;
  SheetSolve s;
  s.sheet = k;
  const Timer timer;
  s.report = bspline::solve_sheet(sheets_[k], energies_[k], active, *solver_, refinement, options_.backend);
  // solve_sheet's time outside its factorizations and solves: assembly, the errors per cell,
  // the conflict checks and the probe.
  check_s += std::max(0.0, timer.seconds() - s.report.analyze_s - s.report.solve_s);
  s.factorization = qp::factorization_note(*solver_);
  s.coefficients = sheets_[k].coefficients();
  return s;
}

void SheetSession::measure(SheetStep& step) const {
  for (const SheetSolve& s : step.sheets) {
    step.energy += s.report.energy;
    step.max_constraint_error = std::max(step.max_constraint_error, s.report.max_constraint_error);
    const bspline::VariationalSheet& sh = sheets_[s.sheet];
    for (const auto& [h, c] : constraints_) {
      if (c.sheet != s.sheet) continue;
      SheetConstraintCheck check;
      check.handle = h;
      const SheetConstraint& k = c.constraint;
      if (k.kind == SheetConstraint::Kind::Point || k.kind == SheetConstraint::Kind::Offset) {
        check.asked = k.target;
        check.achieved = sh.surface().position(sh.coefficients(), k.u, k.v);
        if (k.kind == SheetConstraint::Kind::Offset) check.achieved -= sh.surface().position(sh.coefficients(), k.other.x(), k.other.y());
        check.error = (check.achieved - check.asked).norm();
      } else if (k.kind == SheetConstraint::Kind::Curve || k.kind == SheetConstraint::Kind::Region) {
        check.error = bspline::max_error(bspline::constraint_errors(sh, {k}));
      }
      step.checks.push_back(check);
    }
  }
}

bspline::ObjectiveErrorEstimate SheetSession::estimate_objective_error(std::size_t k) {
  return bspline::estimate_objective_error(sheet(k), energies_[k], active(k), *solver_, options_.backend);
}

}  // namespace fairshape
