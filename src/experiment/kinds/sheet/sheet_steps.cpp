#include "fairshape/experiment/kinds/sheet/sheet_steps.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fairshape/core/config.h"
#include "fairshape/experiment/kinds/sheet/constraint_kinds.h"
#include "fairshape/experiment/kinds/sheet/sheet_files.h"

namespace fairshape {

using bspline::SheetConstraint;

namespace {

SheetSession make_session(SheetRunSpec& spec) {
  std::vector<std::string> names;
  std::vector<bspline::VariationalSheet> sheets;
  for (const SheetSpec& ss : spec.sheets) {
    names.push_back(ss.name);
    sheets.push_back(initial_sheet(ss));
    if (!ss.refine.empty()) sheets.back().refine(ss.refine);
  }
  SheetSessionOptions options;
  options.energy = spec.energy;
  options.refinement = spec.refinement;
  options.backend = spec.implementation;
  return SheetSession(std::move(names), std::move(sheets), options, std::move(spec.solver));
}

// The first step a constraint uses the curve (0 when none does).
int first_use(const SheetRunSpec& spec, const SpaceCurveSpec& c) {
  int first = -1;
  for (const SheetConstraintSpec& cs : spec.constraints)
    if (cs.curve == c.name && (first < 0 || cs.step < first)) first = cs.step;
  return std::max(first, 0);
}

// What a figure draws over a step (vtk/<run>_step<k>_constraints.vtp, read by fairshape
// render beside the step's .vtp): point targets as handles with the offset from where the
// initial sheet was at their (u, v), normal targets where the initial sheet was, and the space
// curves of the active curve constraints.
void add_to_overlay(const std::vector<SheetConstraint>& active, const bspline::HierarchicalSurface& initial,
                    const Eigen::MatrixXd& initial_P, ConstraintOverlay& overlay) {
  for (const SheetConstraint& c : active) {
    if (c.kind == SheetConstraint::Kind::Point) overlay.add_handle(c.target, c.target - initial.position(initial_P, c.u, c.v));
    if (c.kind == SheetConstraint::Kind::Normal) overlay.add_normal(initial.position(initial_P, c.u, c.v), c.target);
    if (c.kind == SheetConstraint::Kind::Curve) overlay.add_curve(c.curve.space);
  }
}

}  // namespace

std::vector<Vec3> curve_at_step(const SpaceCurveSpec& c, const std::vector<Vec3>& base, int step) {
  std::vector<Vec3> pts = base;
  for (const SpaceCurveEdit& e : c.edits) {
    if (e.step > step) continue;
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const double t = static_cast<double>(k) / (pts.size() - 1);
      // A closed curve's bump wraps round its start (t = 0 and 1 are one point, moved alike).
      const double d = (c.closed ? std::min(std::abs(t - e.t), 1 - std::abs(t - e.t)) : std::abs(t - e.t)) / e.radius;
      if (d < 1) pts[k] += 0.5 * (1 + std::cos(M_PI * d)) * e.by;
    }
  }
  return pts;
}

SheetConfigSteps::SheetConfigSteps(SheetRunSpec spec) : spec_(std::move(spec)), session_(make_session(spec_)) {
  for (const SpaceCurveSpec& c : spec_.curves) {
    if (c.from_sheet.empty()) {
      base_curves_[c.name] = c.points;
      continue;
    }
    const bspline::VariationalSheet& sh = session_.sheet(session_.sheet_index(c.from_sheet));
    base_curves_[c.name] = bspline::surface_curve(sh.surface(), sh.coefficients(), c.uv, c.samples);
  }
  for (const SheetConstraintSpec& cs : spec_.constraints)
    if (cs.held == SheetConstraintSpec::Held::Initial) held_[cs.label] = session_.surface_now(session_.sheet_index(cs.sheet));
  for (const SpaceCurveSpec& c : spec_.curves) curves_now_[c.name] = curve_at_step(c, base_curves_.at(c.name), 0);
  free_curves_ = std::make_unique<FreeCurves>(spec_, base_curves_);
  session_.reserve_handles(static_cast<SheetHandle>(spec_.constraints.size()));
}

// The constraint as it acts at `step`: the space curve as it is then, relative targets resolved
// on the initial surface, the held surface, the moves up to then.
SessionConstraint SheetConfigSteps::resolved(const SheetConstraintSpec& cs, int step) const {
  SessionConstraint out;
  out.sheet = session_.sheet_index(cs.sheet);
  const bspline::HierarchicalSurface& initial = session_.initial_surface(out.sheet);
  const Eigen::MatrixXd& initial_P = session_.initial_coefficients(out.sheet);
  SheetConstraint& c = out.constraint;
  c = cs.constraint;
  if (!cs.curve.empty()) {
    c.curve.space = curves_now_.at(cs.curve);
    if (const auto t = traced_on_.find(cs.curve); t != traced_on_.end()) c.curve.traced = t->second;
  }
  if (cs.relative) c.target += initial.position(initial_P, c.u, c.v);
  if (cs.relative && c.kind == SheetConstraint::Kind::Offset) c.target -= initial.position(initial_P, c.other.x(), c.other.y());
  if (cs.held != SheetConstraintSpec::Held::None) c.surface = held_.at(cs.label);
  for (const PointMove& m : cs.moves)
    if (m.step <= step) c.target += m.by;
  return out;
}

// The step's changes: rest-shape actions; curves traced and surfaces held on the sheets as the
// steps before left them (before this step's solve: adding them moves nothing); every
// constraint active now put with its targets of this step (handle: its index in the config),
// the others removed. Joints to variational curves are solved with them (free_curves.h).
SheetEdits SheetConfigSteps::edits_at(int step) {
  SheetEdits e;
  for (const RestShapeAction& a : spec_.actions)
    if (a.step == step)
      e.rest.push_back({a.kind == RestShapeAction::Kind::Install ? RestShapeChange::Kind::Install : RestShapeChange::Kind::Melt,
                        a.sheet.empty() ? std::nullopt : std::optional<std::size_t>(session_.sheet_index(a.sheet))});
  for (const SpaceCurveSpec& c : spec_.curves) {
    if (!c.trace_current || first_use(spec_, c) != step) continue;
    const std::size_t k = session_.sheet_index(c.from_sheet);
    base_curves_[c.name] = bspline::surface_curve(session_.sheet(k).surface(), session_.sheet(k).coefficients(), c.uv, c.samples);
    traced_on_[c.name] = session_.surface_now(k);
  }
  for (const SheetConstraintSpec& cs : spec_.constraints)
    if (cs.held == SheetConstraintSpec::Held::Current && cs.step == step) held_[cs.label] = session_.surface_now(session_.sheet_index(cs.sheet));
  for (const SpaceCurveSpec& c : spec_.curves) curves_now_[c.name] = curve_at_step(c, base_curves_.at(c.name), step);
  for (std::size_t i = 0; i < spec_.constraints.size(); ++i) {
    const SheetConstraintSpec& cs = spec_.constraints[i];
    const SheetHandle h = static_cast<SheetHandle>(i);
    if (cs.joins_free_curve) continue;
    if (cs.active_at(step)) e.put.emplace_back(h, resolved(cs, step));
    else if (session_.constraints().count(h)) e.remove.push_back(h);
  }
  return e;
}

JointSolve SheetConfigSteps::joint_solve(int step, SheetConfigStep& out) {
  return [this, step, &out](std::vector<bspline::VariationalSheet>& sheets, const std::vector<bspline::SheetEnergy>& energies,
                            const std::vector<std::vector<SheetConstraint>>& own) {
    JoinedStep joined = free_curves_->solve_step(spec_, step, session_.solver(), sheets, energies, own, out.curves_now, out.overlay);
    out.free_curves = std::move(joined.curves);
    std::map<std::size_t, JointSheetReport> reports;
    for (auto& [k, js] : joined.sheets) reports[k] = {std::move(js.report), js.factorization};
    return reports;
  };
}

SheetConfigStep SheetConfigSteps::advance() {
  if (next_ >= steps()) throw InvalidInput("the config's " + std::to_string(steps()) + " steps are done");
  SheetConfigStep out;
  out.step = next_;
  const SheetEdits edits = edits_at(out.step);
  out.curves_now = curves_now_;
  SheetChecks checks;
  // The resolution probe costs many solves: on the last step only unless asked for every step.
  checks.curve_probe = spec_.probe_every_step || out.step + 1 == steps();
  out.result = session_.apply(edits, checks, joint_solve(out.step, out));
  curves_now_ = out.curves_now;  // with the variational curves as solved
  for (const SheetSolve& s : out.result.sheets)
    add_to_overlay(session_.active(s.sheet), session_.initial_surface(s.sheet), session_.initial_coefficients(s.sheet), out.overlay);
  ++next_;
  return out;
}

SessionConstraint SheetConfigSteps::read_constraint(const YAML::Node& entry) {
  return parse_config(entry, [&](Config& c) {
    for (const char* key : {"step", "until", "moves"})
      if (c.has(key))
        throw InvalidConfig(c.key_path(key) + ": a session's constraint comes and goes by its steps (add, move, remove), "
                                              "not by a schedule");
    const SheetConfigConstraint read =
        read_sheet_config_constraint(c, {"constraint", spec_.sheets.front().name, spec_.refinement.tolerance});
    const auto* own = std::get_if<SheetConstraintSpec>(&read.spec);
    if (!own)
      throw InvalidConfig(c.key_path("type") + ": a variational curve's constraints and tangent continuity are given with the "
                                               "session's config (valid here: point, tangent, normal, curve, ribbon, offset, region)");
    SheetConstraintSpec cs = *own;
    prepare_sheet_constraint(spec_, cs);
    for (const SpaceCurveSpec& curve : spec_.curves)
      if (curve.name == cs.curve && curve.variational)
        throw InvalidConfig(c.key_path("curve") + ": '" + cs.curve + "' is variational: its joints are given with the session's config");
    const std::size_t k = session_.sheet_index(cs.sheet);
    if (cs.held != SheetConstraintSpec::Held::None) {  // the surface it holds, under a label of its own
      std::ostringstream label;
      label << "session[" << held_.size() << "]";
      cs.label = label.str();
      held_[cs.label] = cs.held == SheetConstraintSpec::Held::Initial
                                 ? std::make_shared<const bspline::SurfaceTrace>(
                                       bspline::SurfaceTrace{session_.initial_surface(k), session_.initial_coefficients(k)})
                                 : session_.surface_now(k);
    }
    c.check_no_unknown_keys();
    return resolved(cs, std::max(next_ - 1, 0));
  });
}

}  // namespace fairshape
