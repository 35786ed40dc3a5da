#include "fairshape/design/regional_edit.h"

#include <algorithm>
#include <map>
#include <optional>
#include <limits>
#include <set>
#include <sstream>

#include "fairshape/core/timer.h"
#include "fairshape/design/multires_constraints.h"
#include "fairshape/problem/anderson_acceleration.h"
#include "fairshape/problem/constrained_system.h"
#include "fairshape/problem/least_squares.h"

namespace fairshape {

namespace {

// One constraint as placed on its own level, with its influence.
struct PlacedTerm {
  DesignConstraints placed;
  Influence influence;
  std::string label;
};

void append(DesignConstraints& to, const DesignConstraints& from) {
  to.points.insert(to.points.end(), from.points.begin(), from.points.end());
  to.normals.insert(to.normals.end(), from.normals.begin(), from.normals.end());
  to.curves.insert(to.curves.end(), from.curves.begin(), from.curves.end());
}

// The lowest level a constraint's points and normals are given on.
int given_level(const DesignConstraints& dc, int finest) {
  int level = finest;
  for (const auto& p : dc.points) level = std::min(level, p.level);
  for (const auto& n : dc.normals) level = std::min(level, n.level);
  return level;
}

std::vector<PlacedTerm> place_terms(const EditTerms& terms, const MultiresSurface& h, int edit_level) {
  if (edit_level < 0 || edit_level > h.levels())
    throw InvalidInput("edit level " + std::to_string(edit_level) + " outside the hierarchy [0, " +
                       std::to_string(h.levels()) + "]");
  const LevelMeshes mesh_at = [&h](int l) -> const SurfaceMesh& { return h.mesh(l); };
  std::vector<PlacedTerm> out;
  for (std::size_t i = 0; i < terms.constraints.size(); ++i) {
    PlacedTerm t;
    t.influence = terms.influence(i);
    terms.constraints[i]->add_on_surface(mesh_at, h.levels(), h.options(), t.placed);
    t.label = !t.placed.points.empty()    ? t.placed.points.front().label
              : !t.placed.normals.empty() ? t.placed.normals.front().label
                                          : "constraint " + std::to_string(i);
    if (!t.influence.held) {
      const int k = t.influence.level_or(edit_level);
      if (k < 0 || k > h.levels())
        throw InvalidInput(t.label + ": influence_level " + std::to_string(k) + " is not in the hierarchy (levels 0.." +
                           std::to_string(h.levels()) + ")");
      const int j = given_level(t.placed, h.levels());
      if (k > j)
        throw InvalidInput(t.label + ": influence level " + std::to_string(k) + " is finer than level " +
                           std::to_string(j) + ", where the constraint is given (it is met on its own level and "
                           "propagated to coarser ones: use influence_level <= " + std::to_string(j) + ")");
    }
    out.push_back(std::move(t));
  }
  return out;
}

// The levels of the passes, coarse to fine: every influence level in use (the edit level when
// only fixed constraints remain, whose targets are zero).
std::vector<int> pass_levels(const std::vector<PlacedTerm>& terms, int edit_level) {
  std::set<int> levels;
  for (const auto& t : terms)
    if (!t.influence.held) levels.insert(t.influence.level_or(edit_level));
  if (levels.empty()) levels.insert(edit_level);
  return {levels.begin(), levels.end()};
}

// What pass k imposes: its own constraints, those of coarser passes and the fixed ones — each
// point or normal on a level ≥ k (coarser levels do not change in this pass).
DesignConstraints imposed_in_pass(const std::vector<PlacedTerm>& terms, int k, int edit_level) {
  DesignConstraints out;
  for (const auto& t : terms) {
    if (!t.influence.held && t.influence.level_or(edit_level) > k) continue;
    for (const auto& p : t.placed.points)
      if (p.level >= k) out.points.push_back(p);
    for (const auto& n : t.placed.normals)
      if (n.level >= k) out.normals.push_back(n);
  }
  return out;
}

// The level-k vertices pass k may move (sorted), or nullopt for the whole level.
std::optional<std::vector<int>> pass_unknowns(const std::vector<PlacedTerm>& terms, const MultiresSurface& h, int k,
                                              int edit_level) {
  std::vector<int> region;
  const int n = h.mesh(k).n_vertices();
  for (const auto& t : terms) {
    if (t.influence.held || t.influence.level_or(edit_level) != k) continue;
    if (t.influence.rings == Influence::kWholeLevel) return std::nullopt;
    const LinearConstraints rows = propagate_constraints(h, k, t.placed);
    std::vector<int> seeds = reached_columns(rows.A);
    for (int c : reached_columns(rows.A_coupled)) seeds.push_back(c % n);  // [Δx; Δy; Δz] columns
    const std::vector<int> grown = grow_rings(h.mesh(k), seeds, t.influence.rings);
    region.insert(region.end(), grown.begin(), grown.end());
  }
  std::sort(region.begin(), region.end());
  region.erase(std::unique(region.begin(), region.end()), region.end());
  return region;
}

// Keeps the rows of A (acting on the columns `cols` of B = A·pick) that reach a kept column.
std::vector<int> rows_reaching(const SparseMatrix& restricted) {
  std::vector<char> reaches(static_cast<std::size_t>(restricted.rows()), 0);
  for (Eigen::Index j = 0; j < restricted.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(restricted, j); it; ++it)
      if (it.value() != 0) reaches[static_cast<std::size_t>(it.row())] = 1;
  std::vector<int> rows;
  for (std::size_t r = 0; r < reaches.size(); ++r)
    if (reaches[r]) rows.push_back(static_cast<int>(r));
  return rows;
}

// The problem on the unknowns U of a level; the other vertices stay where they are (δ = 0),
// so their columns drop out, and a row that reaches no vertex of U cannot change in this pass.
struct Restriction {
  SparseMatrix pick;          // n × |U|: column i picks vertex U[i]
  SparseMatrix keep, keep_c;  // row pickers of the point and the coupled rows that reach U
};

EditProblem restricted_to(const EditProblem& full, const std::vector<int>& U, Restriction& r) {
  r.pick = row_picker(full.H.rows(), U);
  EditProblem p;
  p.anchored = true;
  p.H = SparseMatrix(r.pick.transpose() * full.H * r.pick);
  p.g = r.pick.transpose() * full.g;
  const LinearConstraints& lc = full.constraints;
  const SparseMatrix A = lc.A * r.pick;
  r.keep = row_picker(A.rows(), rows_reaching(A));
  p.constraints.A = SparseMatrix(r.keep.transpose() * A);
  p.constraints.C = r.keep.transpose() * lc.C;
  r.keep_c = row_picker(0, {});
  if (lc.coupled()) {
    const SparseMatrix Ac = lc.A_coupled * block_diagonal(r.pick, 3);
    r.keep_c = row_picker(Ac.rows(), rows_reaching(Ac));
    p.constraints.A_coupled = SparseMatrix(r.keep_c.transpose() * Ac);
    p.constraints.C_coupled = r.keep_c.transpose() * lc.C_coupled;
  }
  return p;
}

SolveSummary combined(const std::vector<RegionalPass>& passes) {
  SolveSummary s;
  s.termination = Termination::Converged;
  std::string detail;
  for (const RegionalPass& p : passes) {
    s.iterations += p.summary.iterations;
    detail += std::string(detail.empty() ? "" : "; ") + "level " + std::to_string(p.level) + ": " +
              std::to_string(p.unknowns) + " of " + std::to_string(p.level_vertices) + " vertices";
    if (!is_success(p.summary.termination) && is_success(s.termination)) {
      s.termination = p.summary.termination;
      s.message = "pass on level " + std::to_string(p.level) + ": " + p.summary.message;
    } else if (s.termination == Termination::Converged) {
      s.termination = p.summary.termination;  // e.g. schedule_completed stays what it was
    }
  }
  const std::string passes_text = std::to_string(passes.size()) + (passes.size() == 1 ? " pass (" : " passes (") + detail + ")";
  s.message = s.message.empty() ? "regions of influence: " + passes_text : s.message + "; " + passes_text;
  return s;
}

// Pass k: its program analysed once, then solved until what its constraints still miss on the
// actual surface is within tolerance. One round is exact when k is the finest level; on a
// coarser one the finer levels' local details turn with the edit, so the surface misses the
// linear rows' answer by a little — the next round, its targets measured again, takes that up.
RegionalPass solve_pass(const std::vector<PlacedTerm>& placed, const EditTerms& energies_only, const MultiresSurface& rest,
                        int k, int edit_level, ConstraintMode mode, Solver& solver, Backend backend,
                        const Config& qp_options, double tolerance, MultiresSurface& edited) {
  constexpr int kMaxRounds = 30, kStallRounds = 3;
  RegionalPass pass;
  pass.level = k;
  pass.level_vertices = rest.mesh(k).n_vertices();
  const DesignConstraints imposed = imposed_in_pass(placed, k, edit_level);
  DesignConstraints none;
  EditProblem full = assemble_edit_problem(energies_only, rest, k, none);
  const Eigen::MatrixXd g_rest = full.g;
  full.constraints = propagate_constraints(rest, k, imposed);  // the rows; each round measures its targets
  const std::optional<std::vector<int>> region = pass_unknowns(placed, rest, k, edit_level);
  Eigen::VectorXi on_level = Eigen::VectorXi::Ones(pass.level_vertices);
  Restriction r;
  EditProblem program;  // PreparedEdit reads its coupled targets at every solve: updated in place
  if (region) {
    on_level.setZero();
    for (int v : *region) on_level(v) = 1;
    full.levels.reset();  // a region is not a level of the hierarchy
    program = restricted_to(full, *region, r);
  } else {
    program = full;
  }
  pass.unknowns = region ? static_cast<int>(region->size()) : pass.level_vertices;
  pass.reached = reached_on_level(rest, k, on_level, rest.levels());
  pass.surface_fraction = pass.reached.sum() / static_cast<double>(pass.reached.size());
  PreparedEdit prepared(program, mode, solver, backend, qp_options);
  pass.analyze_s = prepared.analyze_s();
  // Rounds: x, the pass's change of level k so far, is a fixed point of x ← x + δ(x) (δ: the
  // solve for what the surface built on x still misses); accelerated, since near a tip with
  // large details each round removes only about half of the rest (measured on the cow's nose).
  // Each round sets level k to before + x and re-synthesizes the finer levels from it: the
  // local details are kept, so the result depends on x alone (no copy of the hierarchy needed).
  const MatrixX3 before = edited.mesh(k).positions();
  AndersonAcceleration accelerate(5);
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(program.H.rows(), 3);
  double missing = 0, best = std::numeric_limits<double>::infinity();
  int best_round = 0;
  for (int round = 1;; ++round) {
    // E(Δ_prev + δ) = E(Δ_prev) + ½δᵀHδ + (HΔ_prev − g)ᵀδ: the energy of the whole deformation.
    const Eigen::MatrixXd moved = edited.mesh(k).positions() - rest.mesh(k).positions();
    const Eigen::MatrixXd g = g_rest - full.H * moved;
    LinearConstraints targets = missing_targets(rest, imposed, edited);
    if (region) {
      targets.C = r.keep.transpose() * targets.C;
      targets.C_coupled = r.keep_c.transpose() * targets.C_coupled;
    }
    missing = std::sqrt(targets.C.squaredNorm() + targets.C_coupled.squaredNorm());
    if (missing < best * (1 - 1e-3)) best = missing, best_round = round;
    const bool stalled = round - best_round >= kStallRounds;
    if ((round > 1 && missing <= tolerance) || stalled || round > kMaxRounds) break;
    program.constraints.C_coupled = targets.C_coupled;
    prepared.set_linear_term(region ? Eigen::MatrixXd(r.pick.transpose() * g) : g);
    EditSolution sol = prepared.solve(targets.C);
    pass.solve_s += sol.solve_s;
    pass.rounds = round;
    const int iterations = pass.summary.iterations + sol.summary.iterations;
    pass.summary = sol.summary;
    pass.summary.iterations = iterations;
    // A round's rows, propagated to a coarse level, may be inconsistent (more rows than the level
    // carries): the round's least-squares fit is a step, and the pass measures on the surface
    // what its constraints still miss (below), so constraints_unmet of one round does not end it.
    const Termination t = sol.summary.termination;
    if ((!is_success(t) && t != Termination::ConstraintsUnmet) || !sol.delta.allFinite()) return pass;
    if (t == Termination::ConstraintsUnmet) pass.summary = {Termination::Converged, pass.summary.iterations, -1, "", pass.summary.observe_s};
    const Eigen::VectorXd xs = Eigen::Map<const Eigen::VectorXd>(x.data(), x.size());
    const Eigen::MatrixXd gx = x + sol.delta;
    const Eigen::VectorXd next = accelerate.next(xs, Eigen::Map<const Eigen::VectorXd>(gx.data(), gx.size()));
    x = Eigen::Map<const Eigen::MatrixXd>(next.data(), x.rows(), x.cols());
    edited.set_level_positions(k, before + MatrixX3(region ? Eigen::MatrixXd(r.pick * x) : x));
    edited.synthesize_from(k, DetailSpace::Local);
  }
  if (missing > tolerance) {
    std::ostringstream os;
    os << "its constraints still miss the surface by " << std::scientific << missing << " after " << pass.rounds
       << " rounds (tolerance " << tolerance << ")";
    pass.summary.termination = Termination::ConstraintsUnmet;
    pass.summary.message = os.str();
  }
  return pass;
}

}  // namespace

bool is_regional(const EditTerms& terms) {
  for (const Influence& i : terms.influences)
    if (i.regional()) return true;
  return false;
}

void check_regional_edit(const EditTerms& terms, const MultiresSurface& h, int edit_level, const Solver& solver,
                         ConstraintMode mode) {
  if (terms.energies.empty()) throw InvalidInput("edit: no energy term");
  const std::vector<PlacedTerm> placed = place_terms(terms, h, edit_level);
  for (const auto& t : placed)
    if (!t.influence.held && t.influence.rings != Influence::kWholeLevel && mode == ConstraintMode::Paper &&
        solver.uses_levels())
      throw InvalidInput(t.label + ": a bounded region of influence (influence_rings " +
                         std::to_string(t.influence.rings) + ") is solved on its own vertices, but the solver needs "
                         "every vertex of the level (it is multilevel): use a direct or single-level solver, or a QP "
                         "constraint_mode");
  for (int k : pass_levels(placed, edit_level)) {
    for (const WeightedEnergy& e : terms.energies) e.energy->check_applicable(h.mesh(k));
    const DesignConstraints imposed = imposed_in_pass(placed, k, edit_level);
    if (imposed.points.empty() && imposed.normals.empty()) continue;
    check_constraints(h, k, imposed);
  }
}

RegionalEditResult solve_regional_edit(const EditTerms& terms, const MultiresSurface& rest, int edit_level,
                                       ConstraintMode mode, Solver& solver, Backend backend, const Config& qp_options,
                                       double tolerance) {
  const std::vector<PlacedTerm> placed = place_terms(terms, rest, edit_level);
  const int finest = rest.levels();
  RegionalEditResult out{rest, {}, {}, Eigen::VectorXi::Zero(rest.mesh(finest).n_vertices()), {}, 0, 0, 0, 0};
  for (const auto& t : placed) append(out.placed, t.placed);
  EditTerms energies_only = terms;  // H and g of a level; the constraints are imposed pass by pass
  energies_only.constraints.clear();
  energies_only.influences.clear();

  const double size = (rest.mesh(finest).positions().colwise().maxCoeff() -
                       rest.mesh(finest).positions().colwise().minCoeff()).norm();
  MultiresSurface baseline = rest;  // re-synthesized without an edit: what "did not move" means
  for (int k : pass_levels(placed, edit_level)) {
    RegionalPass pass =
        solve_pass(placed, energies_only, rest, k, edit_level, mode, solver, backend, qp_options, tolerance * size,
                   out.edited);
    out.analyze_s += pass.analyze_s;
    out.solve_s += pass.solve_s;
    for (Eigen::Index v = 0; v < pass.reached.size(); ++v)
      if (pass.reached(v) && out.region(v) == 0) out.region(v) = static_cast<int>(out.passes.size()) + 1;
    const bool failed = !is_success(pass.summary.termination);
    if (out.passes.empty()) baseline.synthesize_from(k, DetailSpace::Local);
    out.passes.push_back(std::move(pass));
    if (failed) break;
  }
  out.summary = combined(out.passes);

  DesignConstraints all;
  int lowest = finest;
  for (const auto& t : placed) append(all, t.placed), lowest = std::min(lowest, given_level(t.placed, finest));
  const LinearConstraints missing = propagate_constraints(rest, lowest, all, &out.edited);
  out.constraint_violation = std::sqrt(missing.C.squaredNorm() + missing.C_coupled.squaredNorm());
  // Outside every region a vertex went through the same operations as without the edit, so it
  // equals the baseline bitwise; against the input it may differ by rounding (the local
  // details' frames turn world → local → world on every synthesis, edit or not).
  const Eigen::MatrixXd moved = out.edited.mesh(finest).positions() - baseline.mesh(finest).positions();
  for (Eigen::Index v = 0; v < moved.rows(); ++v)
    if (out.region(v) == 0) out.outside_region_move = std::max(out.outside_region_move, moved.row(v).norm());
  out.summary.residual = out.constraint_violation;
  if (is_success(out.summary.termination) && out.constraint_violation > tolerance * size) {
    std::ostringstream os;  // a constraint no pass could reach again after a later one moved it
    os << "the constraints miss the result by " << std::scientific << out.constraint_violation << " (tolerance "
       << tolerance * size << ")";
    out.summary.termination = Termination::ConstraintsUnmet;
    out.summary.message = os.str() + "; " + out.summary.message;
  }
  return out;
}

}  // namespace fairshape
