#include "fairshape/design/regional_edit.h"

#include <algorithm>
#include <map>
#include <memory>
#include <optional>
#include <limits>
#include <set>
#include <sstream>

#include "fairshape/core/error.h"
#include "fairshape/core/timer.h"
#include "fairshape/design/multires_constraints.h"
#include "fairshape/mesh/orientation.h"
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
  std::vector<PlacedTerm> out;
  for (std::size_t i = 0; i < terms.constraints.size(); ++i) {
    PlacedTerm t;
    t.influence = terms.influence(i);
    place_constraint(terms, *terms.constraints[i], h, t.placed);
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

// The level-k vertices pass k may move (sorted), or nullopt for the whole level; a constraint
// with influence_rings auto grows by `auto_rings` rings.
std::optional<std::vector<int>> pass_unknowns(const std::vector<PlacedTerm>& terms, const MultiresSurface& h, int k,
                                              int edit_level, int auto_rings) {
  std::vector<int> region;
  const int n = h.mesh(k).n_vertices();
  for (const auto& t : terms) {
    if (t.influence.held || t.influence.level_or(edit_level) != k) continue;
    if (t.influence.rings == Influence::kWholeLevel) return std::nullopt;
    const LinearConstraints rows = propagate_constraints(h, k, t.placed);
    std::vector<int> seeds = reached_columns(rows.A);
    for (int c : reached_columns(rows.A_coupled)) seeds.push_back(c % n);  // [Δx; Δy; Δz] columns
    const int rings = t.influence.rings == Influence::kAutoRings ? auto_rings : t.influence.rings;
    const std::vector<int> grown = grow_rings(h.mesh(k), seeds, rings);
    region.insert(region.end(), grown.begin(), grown.end());
  }
  std::sort(region.begin(), region.end());
  region.erase(std::unique(region.begin(), region.end()), region.end());
  return region;
}

// True when pass k has a constraint whose rings grow until its result does not fold.
bool grows_rings(const std::vector<PlacedTerm>& terms, int k, int edit_level) {
  for (const auto& t : terms)
    if (!t.influence.held && t.influence.level_or(edit_level) == k && t.influence.rings == Influence::kAutoRings)
      return true;
  return false;
}

// True when pass k moves its whole level (pass_unknowns gives nullopt).
bool moves_whole_level(const std::vector<PlacedTerm>& terms, int k, int edit_level) {
  for (const auto& t : terms)
    if (!t.influence.held && t.influence.level_or(edit_level) == k && t.influence.rings == Influence::kWholeLevel)
      return true;
  return false;
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
              std::to_string(p.unknowns) + " of " + std::to_string(p.level_vertices) + " vertices" +
              (p.solved_by.empty() ? "" : ", " + p.solved_by);
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

// What a pass solves each round: the increment of its unknowns for what its constraints still
// miss (`targets`, in the rows' order, restricted to the rows that reach the unknowns), with the
// energy of the whole deformation so far — read from `edited` — as the linear term.
class RoundSolver {
 public:
  virtual ~RoundSolver() = default;
  virtual EditSolution solve(const LinearConstraints& targets, const MultiresSurface& edited) = 0;
  double analyze_s() const { return analyze_s_; }

 protected:
  double analyze_s_ = 0;
};

// The pass's program on level k (its region, or the whole level) solved directly by one
// analysed PreparedEdit.
class DirectRound : public RoundSolver {
 public:
  //! `own`: a solver of its own (the ladder's direct one), used instead of `solver`.
  DirectRound(const EditProblem& full, const std::optional<std::vector<int>>& region, Restriction& r,
              const MultiresSurface& rest, int k, ConstraintMode mode, Solver& solver, std::unique_ptr<Solver> own,
              Backend backend, const Config& qp_options)
      : full_(full), rest_(rest), k_(k), region_(region.has_value()), r_(r), own_(std::move(own)) {
    if (region_) {
      full_.levels.reset();  // a region is not a level of the hierarchy
      program_ = restricted_to(full_, *region, r_);
    } else {
      program_ = full_;
    }
    prepared_ = std::make_unique<PreparedEdit>(program_, mode, own_ ? *own_ : solver, backend, qp_options);
    analyze_s_ = prepared_->analyze_s();
  }

  EditSolution solve(const LinearConstraints& targets, const MultiresSurface& edited) override {
    // E(Δ_prev + δ) = E(Δ_prev) + ½δᵀHδ + (HΔ_prev − g)ᵀδ: the energy of the whole deformation.
    const Eigen::MatrixXd moved = edited.mesh(k_).positions() - rest_.mesh(k_).positions();
    const Eigen::MatrixXd g = full_.g - full_.H * moved;
    program_.constraints.C_coupled = targets.C_coupled;  // PreparedEdit reads them at every solve
    prepared_->set_linear_term(region_ ? Eigen::MatrixXd(r_.pick.transpose() * g) : g);
    return prepared_->solve(targets.C);
  }

 private:
  EditProblem full_, program_;
  const MultiresSurface& rest_;
  int k_;
  bool region_;
  Restriction& r_;
  std::unique_ptr<Solver> own_;
  std::unique_ptr<PreparedEdit> prepared_;  // after own_: destroyed before the solver it uses
};

// A whole-level pass on §5's ladder from level c to k (design/multilevel_edit.h): every level
// carries the pass's rows propagated to it, the same targets (a target belongs to its
// constraint, not to a level) and the energy of the whole deformation so far on that level.
class LadderRound : public RoundSolver {
 public:
  LadderRound(const EditTerms& energies_only, const MultiresSurface& rest, const DesignConstraints& imposed, int k,
              const PassLadder& how, Backend backend)
      : rest_(rest), coarse_(std::min(how.coarse_level, k)) {
    DesignConstraints none;
    ladder_ = assemble_edit_ladder(energies_only, rest, coarse_, k, none);
    for (std::size_t i = 0; i < ladder_.problems.size(); ++i) {
      EditProblem& p = ladder_.problems[i];
      p.constraints = propagate_constraints(rest, coarse_ + static_cast<int>(i), imposed);
      g_rest_.push_back(p.g);
    }
    edit_ = std::make_unique<MultilevelEdit>(ladder_, how.accuracy, how.direct, how.relaxer, *how.finest, backend,
                                             how.coarse_mode);
    analyze_s_ = edit_->analyze_s();
  }

  EditSolution solve(const LinearConstraints& targets, const MultiresSurface& edited) override {
    std::vector<Eigen::MatrixXd> g;
    for (std::size_t i = 0; i < ladder_.problems.size(); ++i) {
      EditProblem& p = ladder_.problems[i];
      FAIRSHAPE_ASSERT(p.constraints.A.rows() == targets.C.rows() && p.constraints.A_coupled.rows() == targets.C_coupled.rows(),
                       "a ladder level's rows and the pass's targets differ in number");
      p.constraints.C = targets.C;
      p.constraints.C_coupled = targets.C_coupled;
      const int l = coarse_ + static_cast<int>(i);
      g.push_back(g_rest_[i] - p.H * (edited.mesh(l).positions() - rest_.mesh(l).positions()));
    }
    edit_->restart_with_linear_terms(g);
    return edit_->solve(1.0);
  }

 private:
  const MultiresSurface& rest_;
  int coarse_;
  EditLadder ladder_;  // MultilevelEdit keeps a reference: never moved after construction
  std::vector<Eigen::MatrixXd> g_rest_;
  std::unique_ptr<MultilevelEdit> edit_;
};

// Pass k: its program analysed once, then solved until what its constraints still miss on the
// actual surface is within tolerance. One round is exact when k is the finest level; on a
// coarser one the finer levels' local details turn with the edit, so the surface misses the
// linear rows' answer by a little — the next round, its targets measured again, takes that up.
RegionalPass solve_pass(const std::vector<PlacedTerm>& placed, const EditTerms& energies_only, const MultiresSurface& rest,
                        int k, int edit_level, ConstraintMode mode, Solver& solver, Backend backend,
                        const Config& qp_options, double tolerance, const PassLadder* ladder, int auto_rings,
                        MultiresSurface& edited) {
  constexpr int kMaxRounds = 30, kStallRounds = 3;
  RegionalPass pass;
  pass.level = k;
  pass.level_vertices = rest.mesh(k).n_vertices();
  const DesignConstraints imposed = imposed_in_pass(placed, k, edit_level);
  const std::optional<std::vector<int>> region = pass_unknowns(placed, rest, k, edit_level, auto_rings);
  Eigen::VectorXi on_level = Eigen::VectorXi::Ones(pass.level_vertices);
  if (region) {
    on_level.setZero();
    for (int v : *region) on_level(v) = 1;
  }
  pass.unknowns = region ? static_cast<int>(region->size()) : pass.level_vertices;
  pass.reached = reached_on_level(rest, k, on_level, rest.levels());
  pass.surface_fraction = pass.reached.sum() / static_cast<double>(pass.reached.size());
  Restriction r;
  std::unique_ptr<RoundSolver> round_solver;
  if (ladder && !region) {
    round_solver = std::make_unique<LadderRound>(energies_only, rest, imposed, k, *ladder, backend);
    pass.solved_by = std::string(to_string(ladder->accuracy)) + " ladder from level " +
                     std::to_string(std::min(ladder->coarse_level, k));
  } else {
    if (ladder) pass.solved_by = "direct";
    if (grows_rings(placed, k, edit_level)) pass.solved_by += (pass.solved_by.empty() ? "" : ", ") + std::to_string(auto_rings) + " rings (auto)";
    DesignConstraints none;
    EditProblem full = assemble_edit_problem(energies_only, rest, k, none);
    full.constraints = propagate_constraints(rest, k, imposed);  // the rows; each round measures its targets
    // Under the ladder a bounded region is solved like the ladder's coarse level: directly.
    round_solver = std::make_unique<DirectRound>(full, region, r, rest, k, ladder ? ladder->coarse_mode : mode, solver,
                                                 ladder ? ladder->direct() : nullptr, backend, qp_options);
  }
  pass.analyze_s = round_solver->analyze_s();
  // Rounds: x, the pass's change of level k so far, is a fixed point of x ← x + δ(x) (δ: the
  // solve for what the surface built on x still misses); accelerated, since near a tip with
  // large details each round removes only about half of the rest (measured on the cow's nose).
  // Each round sets level k to before + x and re-synthesizes the finer levels from it: the
  // local details are kept, so the result depends on x alone (no copy of the hierarchy needed).
  const MatrixX3 before = edited.mesh(k).positions();
  AndersonAcceleration accelerate(5);
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(pass.unknowns, 3);
  double missing = 0, best = std::numeric_limits<double>::infinity();
  int best_round = 0;
  for (int round = 1;; ++round) {
    LinearConstraints targets = missing_targets(rest, imposed, edited);
    if (region) {
      targets.C = r.keep.transpose() * targets.C;
      targets.C_coupled = r.keep_c.transpose() * targets.C_coupled;
    }
    missing = std::sqrt(targets.C.squaredNorm() + targets.C_coupled.squaredNorm());
    if (missing < best * (1 - 1e-3)) best = missing, best_round = round;
    const bool stalled = round - best_round >= kStallRounds;
    if ((round > 1 && missing <= tolerance) || stalled || round > kMaxRounds) break;
    EditSolution sol = round_solver->solve(targets, edited);
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

// Pass k with influence_rings auto: solved on 2 rings, then 4, 8, … while its result folds the
// surface (a face turned against the rest surface), up to the whole level. A region narrower
// than the handle's move has to bend back on itself between the handle and its fixed border
// (measured: papers/boier-martin/README.md, "Regions that fold"); the rings that fit are found
// by looking at the result, which costs one pass on a small region per doubling.
RegionalPass solve_unfolded_pass(const std::vector<PlacedTerm>& placed, const EditTerms& energies_only,
                                 const MultiresSurface& rest, int k, int edit_level, ConstraintMode mode, Solver& solver,
                                 Backend backend, const Config& qp_options, double tolerance, const PassLadder* ladder,
                                 MultiresSurface& edited) {
  const MatrixX3 before = edited.mesh(k).positions();
  const int finest = rest.levels();
  const bool grows = grows_rings(placed, k, edit_level);
  // Folds an earlier pass left are that pass's: this one grows only for the folds it adds.
  const std::size_t folds_before = grows ? flipped_faces(rest.mesh(finest), edited.mesh(finest).positions()).flipped.size() : 0;
  double discarded_analyze_s = 0, discarded_solve_s = 0;  // the attempts that folded cost time too
  for (int rings = Influence::kFirstAutoRings;; rings *= 2) {
    RegionalPass pass = solve_pass(placed, energies_only, rest, k, edit_level, mode, solver, backend, qp_options,
                                   tolerance, ladder, rings, edited);
    pass.analyze_s += discarded_analyze_s;
    pass.solve_s += discarded_solve_s;
    if (!grows || !is_success(pass.summary.termination) || pass.unknowns == pass.level_vertices ||
        flipped_faces(rest.mesh(finest), edited.mesh(finest).positions()).flipped.size() <= folds_before)
      return pass;
    discarded_analyze_s = pass.analyze_s;
    discarded_solve_s = pass.solve_s;
    edited.set_level_positions(k, before);  // undone: level k as it was, the finer levels re-synthesized from it
    edited.synthesize_from(k, DetailSpace::Local);
  }
}

}  // namespace

bool is_regional(const EditTerms& terms) {
  for (const Influence& i : terms.influences)
    if (i.regional()) return true;
  return false;
}

void check_regional_edit(const EditTerms& terms, const MultiresSurface& h, int edit_level, const Solver& solver,
                         ConstraintMode mode, const PassLadder* ladder) {
  if (terms.energies.empty()) throw InvalidInput("edit: no energy term");
  const std::vector<PlacedTerm> placed = place_terms(terms, h, edit_level);
  for (const auto& t : placed)
    if (!ladder && !t.influence.held && t.influence.rings != Influence::kWholeLevel && mode == ConstraintMode::Paper &&
        solver.uses_levels())
      throw InvalidInput(t.label + ": a bounded region of influence (influence_rings " +
                         (t.influence.rings == Influence::kAutoRings ? std::string("auto") : std::to_string(t.influence.rings)) +
                         ") is solved on its own vertices, but the solver needs "
                         "every vertex of the level (it is multilevel): use a direct or single-level solver, or a QP "
                         "constraint_mode");
  for (int k : pass_levels(placed, edit_level)) {
    // A whole-level pass under the ladder is solved on levels min(coarse, k)..k.
    const bool on_ladder = ladder && moves_whole_level(placed, k, edit_level);
    const DesignConstraints imposed = imposed_in_pass(placed, k, edit_level);
    for (int l = on_ladder ? std::min(ladder->coarse_level, k) : k; l <= k; ++l) {
      for (const WeightedEnergy& e : terms.energies) e.energy->check_applicable(h.mesh(l));
      if (!imposed.points.empty() || !imposed.normals.empty()) check_constraints(h, l, imposed);
    }
  }
}

RegionalEditResult solve_regional_edit(const EditTerms& terms, const MultiresSurface& rest, int edit_level,
                                       ConstraintMode mode, Solver& solver, Backend backend, const Config& qp_options,
                                       double tolerance, const PassLadder* ladder) {
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
    RegionalPass pass = solve_unfolded_pass(placed, energies_only, rest, k, edit_level, mode, solver, backend,
                                            qp_options, tolerance * size, ladder, out.edited);
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
