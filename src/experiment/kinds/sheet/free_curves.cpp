#include "fairshape/experiment/kinds/sheet/free_curves.h"

#include <algorithm>
#include <array>
#include <numeric>

#include "fairshape/core/message_format.h"
#include "fairshape/experiment/kinds/sheet/constraint_schedule.h"
#include "fairshape/experiment/metric_format.h"
#include "fairshape/experiment/run_basics.h"
#include "fairshape/qp/range_space_solver.h"

namespace fairshape {

using bspline::CurveConstraint;

void read_variational(Config& c, SpaceCurveSpec& s) {
  Config v = c.child("variational", "a variational curve {spans, degree, alpha, beta}: it starts as the least-squares fit of the "
                                    "curve's form and moves by its curve_point / curve_tangent constraints and the sheets joined to it");
  s.variational = c.has("variational");
  s.curve_shape.spans = v.get_int("spans", s.curve_shape.spans, 1, 4096,
                                  "base spans of the clamped hierarchical B-spline X(t), t in [0, 1] (refinement.tolerance "
                                  "refines them locally)");
  s.curve_shape.degree = v.get_int("degree", s.curve_shape.degree, bspline::kMinDegree, bspline::kMaxDegree, "B-spline degree");
  s.curve_energy.alpha = v.get_number("alpha", s.curve_energy.alpha, 0, 1e12, "stretching weight: integral of alpha |X'|^2 (design units)");
  s.curve_energy.beta = v.get_number("beta", s.curve_energy.beta, 0, 1e12, "bending weight: integral of beta |X''|^2 (design units)");
  v.check_no_unknown_keys();
  if (!s.variational) return;
  if (s.curve_energy.alpha == 0 && s.curve_energy.beta == 0)
    throw InvalidConfig(v.key_path("beta") + ": alpha and beta are both 0 (the curve would have no energy to minimize)");
  if (!s.edits.empty())
    throw InvalidConfig(c.key_path("edits") + ": a variational curve moves by its constraints (curve_point, curve_tangent) and the "
                                               "sheets joined to it, not by edits");
  if (s.closed)
    throw InvalidConfig(c.key_path("variational") + ": a variational curve is an open (clamped) B-spline; this curve is closed");
}

const std::vector<std::string>& curve_constraint_types() {
  static const std::vector<std::string> types{"curve_point", "curve_tangent"};
  return types;
}

bool is_curve_constraint(const Config& c) {
  if (!c.has("type") || !c.node()["type"].IsScalar()) return false;
  const std::string type = c.node()["type"].Scalar();
  const auto& types = curve_constraint_types();
  return std::find(types.begin(), types.end(), type) != types.end();
}

CurveConstraintSpec read_curve_constraint(Config& c, const std::string& label) {
  CurveConstraintSpec s;
  s.label = s.constraint.label = label;
  const std::string type = c.get_choice("type", "curve_point", curve_constraint_types(), "a variational curve's own constraint");
  s.curve = c.require<std::string>("curve", "the variational curve it acts on");
  s.constraint.t = c.get_number("t", 0.5, 0, 1, "curve parameter t in [0, 1] (the points of its form are equally spaced in t)");
  read_schedule(c, s.step, s.until);
  if (type == "curve_point") {
    s.constraint.kind = CurveConstraint::Kind::Point;
    s.relative = c.has("by");
    if (s.relative && c.has("target")) throw InvalidConfig(c.key_path("by") + ": give target or by, not both");
    if (!s.relative && !c.has("target") && !c.documenting())
      throw InvalidConfig(c.key_path("target") + ": give target (a world position) or by (an offset from the initial curve's point)");
    s.constraint.target = s.relative ? read_vec3(c, "by", Vec3::Zero(), "offset from the initial curve's point X(t)")
                                     : read_vec3(c, "target", Vec3::Zero(), "world position (or give `by`)");
    if (!s.relative) (void)c.get<std::vector<double>>("by", {0, 0, 0}, "offset from the initial curve's point X(t)");
    s.moves = read_moves(c, s.step);
  } else {
    s.constraint.kind = CurveConstraint::Kind::Tangent;
    s.constraint.target = read_vec3(c, "target", Vec3::UnitX(), "dX/ds in design units (per unit length: a unit vector keeps the speed)");
  }
  c.check_no_unknown_keys();
  return s;
}

bool is_tangent_continuity(const Config& c) {
  return c.has("type") && c.node()["type"].IsScalar() && c.node()["type"].Scalar() == "tangent_continuity";
}

TangentContinuitySpec read_tangent_continuity(Config& c, const std::string& label) {
  TangentContinuitySpec s;
  s.label = label;
  (void)c.get<std::string>("type", "tangent_continuity", "two joined sheets made tangent-continuous across their curve");
  s.curve = c.require<std::string>("curve", "the variational curve both sheets are joined to");
  const auto sheets = c.get<std::vector<std::string>>("sheets", {}, "the two sheets [a, b], each joined to the curve by one curve constraint");
  if (!c.documenting() && (sheets.size() != 2 || sheets[0] == sheets[1]))
    throw InvalidConfig(c.key_path("sheets") + ": give two different sheets [a, b]");
  const auto keep = c.get<std::vector<std::string>>("keep", {"left", "right"},
                                                    "per sheet, the side of its joint's (u, v) curve (left or right of its direction) "
                                                    "the design keeps: crossing the curve leaves one and enters the other");
  if (keep.size() != 2) throw InvalidConfig(c.key_path("keep") + ": give two sides [left|right, left|right]");
  for (std::size_t i = 0; i < 2; ++i) {
    if (keep[i] != "left" && keep[i] != "right")
      throw InvalidConfig(c.key_path("keep") + ": '" + keep[i] + "' is not a side (valid: left, right)");
    s.keep_left[i] = keep[i] == "left";
    if (!c.documenting()) s.sheets[i] = sheets[i];
  }
  c.check_no_unknown_keys();
  return s;
}

void check_free_curves(SheetRunSpec& s) {
  const auto curve_named = [&](const std::string& name) {
    return std::find_if(s.curves.begin(), s.curves.end(), [&](const SpaceCurveSpec& c) { return c.name == name; });
  };
  for (const CurveConstraintSpec& cs : s.curve_constraints) {
    const auto it = curve_named(cs.curve);
    if (it == s.curves.end()) throw InvalidConfig(cs.label + ".curve: no space curve named '" + cs.curve + "'");
    if (!it->variational)
      throw InvalidConfig(cs.label + ".curve: '" + cs.curve + "' is not a variational curve (give it variational: {spans, ...})");
  }
  std::vector<std::string> joined_sheets;
  for (SheetConstraintSpec& cs : s.constraints) {
    if (cs.curve.empty() || !curve_named(cs.curve)->variational) continue;
    cs.joins_free_curve = true;
    if (cs.constraint.formulation != bspline::CurveFormulation::Mortar)
      throw InvalidConfig(cs.label + ".formulation: a sheet is joined to a variational curve by the mortar rows only");
    if (cs.constraint.ribbon)
      throw InvalidConfig(cs.label + ".type: a ribbon along a variational curve is not supported (valid here: curve; tangent "
                          "continuity across the joint is type tangent_continuity)");
    joined_sheets.push_back(cs.sheet);
  }
  for (const SheetConstraintSpec& cs : s.constraints)
    if (cs.constraint.kind == bspline::SheetConstraint::Kind::Normal &&
        std::find(joined_sheets.begin(), joined_sheets.end(), cs.sheet) != joined_sheets.end())
      throw InvalidConfig(cs.label + ".type: normal constraints are not supported on a sheet joined to a variational curve (sheet '" +
                          cs.sheet + "')");
  for (const TangentContinuitySpec& tc : s.tangent_continuity) {
    const auto it = curve_named(tc.curve);
    if (it == s.curves.end()) throw InvalidConfig(tc.label + ".curve: no space curve named '" + tc.curve + "'");
    if (!it->variational) throw InvalidConfig(tc.label + ".curve: '" + tc.curve + "' is not a variational curve");
    for (const std::string& sheet : tc.sheets) {
      const auto joints = std::count_if(s.constraints.begin(), s.constraints.end(), [&](const SheetConstraintSpec& cs) {
        return cs.joins_free_curve && cs.curve == tc.curve && cs.sheet == sheet;
      });
      if (joints != 1)
        throw InvalidConfig(tc.label + ".sheets: sheet '" + sheet + "' has " + std::to_string(joints) + " curve constraints joining it to '" +
                            tc.curve + "' (tangent continuity needs exactly one)");
    }
  }
  const auto free = std::find_if(s.curves.begin(), s.curves.end(), [](const SpaceCurveSpec& c) { return c.variational; });
  if (free == s.curves.end()) return;
  const std::string which = " with a variational curve (curves[" + std::to_string(free - s.curves.begin()) + "], '" + free->name + "')";
  if (s.estimate_objective_error) throw InvalidConfig("refinement.estimate_objective_error: not supported in a run" + which);
}

std::vector<std::string> free_curve_step_row(int step, const FreeCurveStep& c) {
  return {std::to_string(step), "curve:" + c.name, std::to_string(c.dofs), std::to_string(c.levels), std::to_string(c.rows), "0",
          num(c.residual), num(c.max_error), num(c.energy), std::to_string(c.spans_refined), std::to_string(c.rounds), "0", "0",
          c.factorization, "", "", "", ""};
}

FreeCurves::FreeCurves(const SheetRunSpec& spec, const std::map<std::string, std::vector<Vec3>>& initial_polylines) {
  for (std::size_t i = 0; i < spec.curves.size(); ++i) {
    const SpaceCurveSpec& c = spec.curves[i];
    if (!c.variational) continue;
    try {
      curves_.emplace_back(c.curve_shape, initial_polylines.at(c.name));
    } catch (const InvalidInput& e) {
      throw InvalidInput("curves[" + std::to_string(i) + "] ('" + c.name + "'): " + e.what());
    }
    spec_index_.push_back(i);
  }
  initial_ = curves_;
}

namespace {

// Union-find over the sheets (0..S−1) and the free curves (S..S+F−1) joined this step.
struct Groups {
  std::vector<std::size_t> parent;
  explicit Groups(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), std::size_t{0}); }
  std::size_t find(std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::size_t a, std::size_t b) { parent[find(a)] = find(b); }
};

struct Group {
  std::vector<std::size_t> sheets, curves;  // sheet indices, free-curve indices
  std::vector<const SheetConstraintSpec*> joints;
};

}  // namespace

JoinedStep FreeCurves::solve_step(const SheetRunSpec& spec, int step, qp::QpSolver& solver, std::vector<bspline::VariationalSheet>& sheets,
                                  const std::vector<bspline::SheetEnergy>& energies,
                                  const std::vector<std::vector<bspline::SheetConstraint>>& own,
                                  std::map<std::string, std::vector<Vec3>>& curves_now, ConstraintOverlay& overlay) {
  JoinedStep out;
  const std::size_t S = sheets.size(), F = curves_.size();
  const auto free_index = [&](const std::string& name) {
    std::size_t f = 0;
    while (f < F && spec.curves[spec_index_[f]].name != name) ++f;
    return f;
  };
  const auto sheet_index = [&](const std::string& name) {
    std::size_t k = 0;
    while (k < S && spec.sheets[k].name != name) ++k;
    return k;
  };
  // The free curves' own constraints active now, targets resolved (by: from the initial fit).
  std::vector<std::vector<CurveConstraint>> constraints(F);
  for (const CurveConstraintSpec& cs : spec.curve_constraints) {
    if (!cs.active_at(step)) continue;
    const std::size_t f = free_index(cs.curve);
    CurveConstraint c = cs.constraint;
    if (cs.relative) c.target += initial_[f].position(c.t);
    for (const PointMove& m : cs.moves)
      if (m.step <= step) c.target += m.by;
    constraints[f].push_back(c);
  }
  Groups groups(S + F);
  std::vector<bool> acted_on(F, false);  // a curve nothing acts on keeps its shape
  for (std::size_t f = 0; f < F; ++f) acted_on[f] = !constraints[f].empty();
  for (const SheetConstraintSpec& cs : spec.constraints)
    if (cs.joins_free_curve && cs.active_at(step)) {
      groups.unite(sheet_index(cs.sheet), S + free_index(cs.curve));
      acted_on[free_index(cs.curve)] = true;
    }
  std::map<std::size_t, Group> by_root;
  for (std::size_t f = 0; f < F; ++f)
    if (acted_on[f]) by_root[groups.find(S + f)].curves.push_back(f);
  for (std::size_t k = 0; k < S; ++k)
    if (by_root.count(groups.find(k))) by_root[groups.find(k)].sheets.push_back(k);
  for (const SheetConstraintSpec& cs : spec.constraints)
    if (cs.joins_free_curve && cs.active_at(step)) by_root[groups.find(S + free_index(cs.curve))].joints.push_back(&cs);

  for (const auto& [root, g] : by_root) {
    bspline::JoinedDesign d;
    for (std::size_t k : g.sheets) d.sheets.push_back({&sheets[k], energies[k], own[k]});
    for (std::size_t f : g.curves) d.curves.push_back({&curves_[f], spec.curves[spec_index_[f]].curve_energy, constraints[f]});
    for (const SheetConstraintSpec* cs : g.joints) {
      const auto local_sheet = std::find(g.sheets.begin(), g.sheets.end(), sheet_index(cs->sheet)) - g.sheets.begin();
      const auto local_curve = std::find(g.curves.begin(), g.curves.end(), free_index(cs->curve)) - g.curves.begin();
      d.joints.push_back({static_cast<int>(local_sheet), static_cast<int>(local_curve), cs->constraint.curve.uv, cs->label});
    }
    // Tangent continuity between two of this group's joints, while both are active.
    for (const TangentContinuitySpec& tc : spec.tangent_continuity) {
      std::array<int, 2> joint{-1, -1};
      for (std::size_t j = 0; j < g.joints.size(); ++j)
        for (int side = 0; side < 2; ++side)
          if (g.joints[j]->curve == tc.curve && g.joints[j]->sheet == tc.sheets[side]) joint[side] = static_cast<int>(j);
      if (joint[0] >= 0 && joint[1] >= 0) d.tangent_joints.push_back({joint[0], joint[1], tc.keep_left[0], tc.keep_left[1], tc.label});
    }
    bspline::JoinedReport r = bspline::solve_joined(d, solver, spec.implementation, spec.refinement);
    for (std::size_t k = 0; k < r.tangent_error.size(); ++k)  // what continuity was achieved, pointwise
      r.message += std::string(r.message.empty() ? "" : "; ") + d.tangent_joints[k].label + ": max |dw1/dn1 + dw2/dn2| " +
                   sci(r.tangent_error[k]);
    const std::string factorization = qp::factorization_note(solver);
    const bool measured = !r.sheet_energy.empty() || !r.curve_energy.empty();
    for (std::size_t i = 0; i < g.sheets.size(); ++i) {
      JoinedSheetStep& js = out.sheets[g.sheets[i]];
      bspline::DesignReport& dr = js.report;
      dr.qp = r.qp;
      dr.qp.p.resize(0, 0);
      dr.rounds = r.rounds;
      dr.spans_refined = r.sheet_spans_refined[i];
      dr.message = r.message;
      dr.constraint_rows = r.sheet_rows[i];
      js.factorization = factorization;
      if (i == 0) dr.analyze_s = r.analyze_s, dr.solve_s = r.solve_s;  // the group's time, counted once
      else dr.qp.dropped_rows = 0;
      if (!measured) continue;
      dr.qp.constraint_residual = r.sheet_residual[i];
      dr.energy = r.sheet_energy[i];
      dr.errors_per_round = {r.sheet_errors[i]};
      dr.max_constraint_error = bspline::max_error(r.sheet_errors[i]);
      if (i < r.sheet_curve_probe.size()) {
        const bspline::CurveConvergence& probe = r.sheet_curve_probe[i];
        dr.curve_error = probe.error, dr.curve_alone_error = probe.alone_error;
        dr.curve_error_refined = probe.refined_error, dr.curve_error_limit = probe.limit;
      }
    }
    for (std::size_t i = 0; i < g.curves.size(); ++i) {
      FreeCurveStep c;
      c.name = spec.curves[spec_index_[g.curves[i]]].name;
      c.dofs = curves_[g.curves[i]].dof_count();
      c.levels = curves_[g.curves[i]].basis().level_count();
      c.spans_refined = r.curve_spans_refined[i];
      c.rounds = r.rounds;
      c.rows = r.curve_rows[i];
      c.termination = r.qp.summary.termination;
      c.message = r.message;
      c.factorization = factorization;
      if (measured) {
        c.residual = r.curve_residual[i], c.energy = r.curve_energy[i];
        // Its own constraints and the joint gaps sampled at its leaves: the errors refinement
        // judged, so that runs.csv's max_constraint_error is the number its message quotes.
        c.max_error = r.curve_error[i];
        for (double e : r.curve_leaf_errors[i]) c.max_error = std::max(c.max_error, e);
      }
      out.curves.push_back(c);
    }
  }
  // Every free curve as it is now (for curves/*.obj and the overlay), dense enough to show its
  // spans; the point targets as handles from where the initial curve had them.
  for (std::size_t f = 0; f < F; ++f) {
    const SpaceCurveSpec& c = spec.curves[spec_index_[f]];
    curves_now[c.name] = curves_[f].sample(std::max(c.samples, 8 * static_cast<int>(curves_[f].basis().leaf_cells().size()) + 1));
    if (!acted_on[f]) continue;
    overlay.add_curve(curves_now[c.name]);
    for (const CurveConstraint& cc : constraints[f])
      if (cc.kind == CurveConstraint::Kind::Point) overlay.add_handle(cc.target, cc.target - initial_[f].position(cc.t));
  }
  return out;
}

}  // namespace fairshape
