#include "fairshape/design/surface_edit_session.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fairshape/core/error.h"
#include "fairshape/core/timer.h"
#include "fairshape/design/multires_constraints.h"
#include "fairshape/problem/constrained_system.h"

namespace fairshape {

namespace {

std::string accuracy_name(const std::optional<Accuracy>& mode) {
  return mode ? std::string(to_string(*mode)) : std::string("single-level");
}

}  // namespace

SurfaceEditSession::SurfaceEditSession(std::shared_ptr<const MultiresSurface> rest, std::vector<SessionEnergy> energies,
                                       std::vector<SessionConstraint> constraints, SurfaceEditOptions options)
    : rest_(std::move(rest)), energies_(std::move(energies)), options_(std::move(options)) {
  if (!rest_) throw InvalidInput("surface edit session: no hierarchy");
  if (!options_.solver) throw InvalidInput("surface edit session: no solver");
  level_ = options_.level < 0 ? rest_->levels() : options_.level;
  if (level_ > rest_->levels())
    throw InvalidInput("surface edit session: edit level " + std::to_string(level_) + " is not in the hierarchy (levels 0.." +
                       std::to_string(rest_->levels()) + ")");
  coarse_ = level_;
  if (options_.ladder) {
    options_.ladder->finest = options_.solver.get();
    coarse_ = options_.ladder->coarse_level;
    if (coarse_ > level_)
      throw InvalidInput("surface edit session: the ladder's coarse level " + std::to_string(coarse_) +
                         " is above the edit level " + std::to_string(level_));
  }
  frame_rows_ = options_.frame_rows;
  for (SessionConstraint& c : constraints) handles_.push_back(Handle{std::move(c), true, 0, 0, std::nullopt});
  prepare_rows();
}

SurfaceEditSession::~SurfaceEditSession() = default;

EditTerms SurfaceEditSession::terms() const {
  EditTerms t;
  for (const SessionEnergy& e : energies_) t.energies.push_back({e.energy.get(), e.weight});
  for (const Handle& h : handles_)
    if (h.live) {
      t.constraints.push_back(h.c.constraint.get());
      t.influences.push_back(h.c.influence);
    }
  t.positions = options_.positions;
  t.levels = options_.levels;
  t.frame_rows_for_auto_normals = frame_rows_;
  return t;
}

bool SurfaceEditSession::regional() const { return is_regional(terms()); }

std::vector<int> SurfaceEditSession::handles() const {
  std::vector<int> live;
  for (std::size_t h = 0; h < handles_.size(); ++h)
    if (handles_[h].live) live.push_back(static_cast<int>(h));
  return live;
}

const MultiresSurface& SurfaceEditSession::current() const {
  if (regional_result_) return *regional_result_;
  return check_ ? check_->edited() : *rest_;
}

const std::vector<Eigen::MatrixXd>& SurfaceEditSession::level_solutions() const {
  static const std::vector<Eigen::MatrixXd> none;
  const auto it = last_mode_ ? modes_.find(*last_mode_) : modes_.end();
  return it == modes_.end() ? none : it->second->level_solutions();
}

const EditProblem& SurfaceEditSession::problem() const {
  if (ladder_.problems.empty())
    throw InvalidInput("surface edit session: an edit with regions of influence assembles one problem per pass");
  return ladder_.problems.back();
}

SurfaceEditSession::Handle& SurfaceEditSession::handle(int h) {
  if (h < 0 || h >= static_cast<int>(handles_.size()))
    throw InvalidInput("handle " + std::to_string(h) + ": no such handle (the session has made " +
                       std::to_string(handles_.size()) + ", numbered from 0)");
  if (!handles_[static_cast<std::size_t>(h)].live) throw InvalidInput("handle " + std::to_string(h) + " was removed");
  return handles_[static_cast<std::size_t>(h)];
}

void SurfaceEditSession::prepare_rows() {
  if (regional()) {  // the passes place and propagate per solve; checked now, as a run is validated
    check_regional_edit(terms(), *rest_, level_, *options_.solver, options_.mode, options_.ladder ? &*options_.ladder : nullptr);
    return;
  }
  if (ladder_.problems.empty()) {  // H of each level: the constraints do not enter it, so add and remove keep it
    EditTerms energies_only = terms();
    energies_only.constraints.clear();
    energies_only.influences.clear();
    DesignConstraints none;
    ladder_ = assemble_edit_ladder(energies_only, *rest_, coarse_, level_, none);
  }
  place();
}

void SurfaceEditSession::place() {
  const EditTerms t = terms();
  DesignConstraints placed;
  for (Handle& h : handles_) {
    if (!h.live) continue;
    h.first = placed.points.size();
    place_constraint(t, *h.c.constraint, *rest_, placed);
    h.last = placed.points.size();
  }
  // Placed once and propagated to each level (Table 1): every level's rows come in the same order.
  for (std::size_t k = 0; k < ladder_.problems.size(); ++k)
    ladder_.problems[k].constraints = propagate_constraints(*rest_, coarse_ + static_cast<int>(k), placed);
  rows_ = point_rows(*rest_, level_, placed.points);
  configured_C_ = ladder_.problems.back().constraints.C;
  configured_ = placed;
  placed_ = std::move(placed);
  apply_targets();
}

void SurfaceEditSession::apply_targets() {
  targets_ = scale_ * configured_C_;
  for (std::size_t i = 0; i < placed_.points.size(); ++i) placed_.points[i].offset = scale_ * configured_.points[i].offset;
  for (const Handle& h : handles_) {
    if (!h.live || !h.moved) continue;
    for (std::size_t i = h.first; i < h.last; ++i) {
      targets_.row(rows_[i]) = h.moved->transpose();
      placed_.points[i].offset = *h.moved;
    }
  }
  for (EditProblem& p : ladder_.problems) p.constraints.C = targets_;
}

void SurfaceEditSession::forget_prepared() {
  prepared_.reset();
  modes_.clear();
}

int SurfaceEditSession::add(SessionConstraint c) {
  handles_.push_back(Handle{std::move(c), true, 0, 0, std::nullopt});
  forget_prepared();
  try {
    prepare_rows();
  } catch (...) {  // the session stays as it was; the number stays taken
    handles_.back().live = false;
    prepare_rows();
    throw;
  }
  return static_cast<int>(handles_.size()) - 1;
}

void SurfaceEditSession::remove(int h) {
  handle(h).live = false;
  forget_prepared();
  prepare_rows();
}

void SurfaceEditSession::move(int h, const Vec3& offset) {
  Handle& moved = handle(h);
  if (regional())
    throw InvalidInput("move handle " + std::to_string(h) + ": an edit with regions of influence is solved in passes from "
                       "its constraints as given (design/regional_edit.h)");
  if (!offset.allFinite()) throw InvalidInput("move handle " + std::to_string(h) + ": the target is not finite");
  // Rows are shared by points on one vertex with one target (point_rows): another constraint
  // holding a vertex of this handle elsewhere is the conflict propagate_constraints refuses.
  std::vector<int> own(rows_.begin() + static_cast<std::ptrdiff_t>(moved.first),
                       rows_.begin() + static_cast<std::ptrdiff_t>(moved.last));
  std::sort(own.begin(), own.end());
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    if (i >= moved.first && i < moved.last) continue;
    if (!std::binary_search(own.begin(), own.end(), rows_[i])) continue;
    if ((placed_.points[i].offset - offset).norm() <= 1e-12 * (1.0 + offset.norm())) continue;
    std::ostringstream os;
    os << "move handle " << h << ": vertex " << placed_.points[i].vertex << " of level " << placed_.points[i].level
       << " is also held by " << placed_.points[i].label << " at [" << placed_.points[i].offset.transpose() << "]";
    throw InvalidInput(os.str());
  }
  moved.moved = offset;
  apply_targets();
}

void SurfaceEditSession::scale(double s) {
  if (!std::isfinite(s)) throw InvalidInput("scale: not finite");
  if (regional())
    throw InvalidInput("scale: an edit with regions of influence is solved in passes from its constraints as given");
  scale_ = s;
  for (Handle& h : handles_) h.moved.reset();
  apply_targets();
}

SurfaceEditStep SurfaceEditSession::solve(const IterationCallback& cb) {
  return solve_step(options_.ladder ? std::optional<Accuracy>(options_.ladder->accuracy) : std::nullopt, cb);
}

SurfaceEditStep SurfaceEditSession::solve(Accuracy mode, const IterationCallback& cb) {
  if (!options_.ladder)
    throw InvalidInput("solve(" + std::string(to_string(mode)) + "): §5's modes need the session's ladder "
                       "(problem.accuracy interactive, improved or converged)");
  return solve_step(mode, cb);
}

SurfaceEditStep SurfaceEditSession::solve_step(std::optional<Accuracy> mode, const IterationCallback& cb) {
  SurfaceEditStep step;
  double earlier_s = 0;
  const auto attempt = [&](bool frame_rows) {
    if (frame_rows) {  // another problem: the normals' rows change (constraint.h NormalRows)
      earlier_s = step.solve_s + step.check_s;
      frame_rows_ = true;
      forget_prepared();
      prepare_rows();
    }
    step = SurfaceEditStep{};
    step.accuracy = accuracy_name(mode);
    last_mode_ = mode;
    const Timer t;
    if (regional()) solve_regional(step);
    else step.solution = solve_assembled(mode, cb, step.rotation_rounds);
    step.solve_s = t.seconds();
    finish(step);
    return step.orientation;
  };
  std::string note;
  if (options_.orient_normals) note = solve_orienting_normals(attempt);
  else attempt(false);
  if (!note.empty()) {
    step.solve_s += earlier_s;
    step.solution.summary.message = noted(note, step.solution.summary.message);
    step.summary.message = noted(note, step.summary.message);
  }
  return step;
}

EditSolution SurfaceEditSession::solve_assembled(std::optional<Accuracy> mode, const IterationCallback& cb, int& rounds) {
  const EditProblem& p = ladder_.problems.back();
  if (mode) {
    std::unique_ptr<MultilevelEdit>& edit = modes_[*mode];
    const PassLadder& l = *options_.ladder;
    if (!edit) {
      edit = std::make_unique<MultilevelEdit>(ladder_, *mode, l.direct, l.relaxer, *options_.solver, options_.backend,
                                              l.coarse_mode);
      ++preparations_;
    }
    return edit->solve(targets_, cb);
  }
  if (options_.rotations.iterations > 0) {
    const RotationAwareSolution r = solve_rotation_aware(p, terms().energies, rest_->mesh(level_), options_.mode,
                                                         *options_.solver, options_.backend, options_.qp_options,
                                                         options_.rotations);
    rounds = r.rounds;
    return r.solution;
  }
  if (!prepared_) {
    prepared_ = std::make_unique<PreparedEdit>(p, options_.mode, *options_.solver, options_.backend, options_.qp_options);
    ++preparations_;
  }
  // A drag step starts where the last one ended (iterative solvers; the direct modes ignore it).
  const Eigen::MatrixXd* start = previous_.size() ? &previous_ : options_.initial.size() ? &options_.initial : nullptr;
  EditSolution sol = prepared_->solve(targets_, cb, start);
  if (sol.delta.allFinite()) previous_ = sol.delta;
  return sol;
}

void SurfaceEditSession::solve_regional(SurfaceEditStep& step) {
  const EditTerms t = terms();
  RegionalEditResult r = solve_regional_edit(t, *rest_, level_, options_.mode, *options_.solver, options_.backend,
                                             options_.qp_options, options_.constraint_tolerance,
                                             options_.ladder ? &*options_.ladder : nullptr);
  step.regional = true;
  step.solution.summary = r.summary;
  step.solution.analyze_s = r.analyze_s;
  step.solution.solve_s = r.solve_s;
  step.solution.constraint_residual = r.constraint_violation;
  step.passes = std::move(r.passes);
  step.region = std::move(r.region);
  step.outside_region_move = r.outside_region_move;
  placed_ = std::move(r.placed);
  if (!step.passes.empty() && !is_success(r.summary.termination)) return;  // no surface to measure
  if (r.outside_region_move > 0) {  // cannot happen by construction: a bug, never a quiet number
    step.solution.summary.termination = Termination::NumericalFailure;
    std::ostringstream os;
    os << "a vertex outside every region of influence moved by " << r.outside_region_move;
    step.solution.summary.message = noted(step.solution.summary.message, os.str());
  }
  step.solution.delta = r.edited.mesh(level_).positions() - rest_->mesh(level_).positions();
  regional_result_ = std::move(r.edited);
}

void SurfaceEditSession::finish(SurfaceEditStep& step) {
  const EditSolution& sol = step.solution;
  step.summary = sol.summary;
  step.constraint_residual = sol.constraint_residual;
  const bool failed = !sol.delta.allFinite() || sol.delta.size() == 0 || sol.summary.termination == Termination::NumericalFailure;
  if (failed) return;
  const Timer t;
  if (step.regional) {
    step.orientation = check_orientation(*rest_, *regional_result_, placed_);
    if (!energy_only_) {  // the energy of the whole deformation on the edit level
      EditTerms energies_only = terms();
      energies_only.constraints.clear();
      energies_only.influences.clear();
      DesignConstraints none;
      energy_only_ = assemble_edit_problem(energies_only, *rest_, level_, none);
    }
    step.energy = edit_energy(*energy_only_, sol.delta);
  } else {
    if (!check_) check_ = std::make_unique<StepOrientationCheck>(*rest_, level_, placed_);
    step.orientation = (*check_)(sol.delta);
    step.energy = edit_energy(ladder_.problems.back(), sol.delta);
  }
  step.check_s = t.seconds();
  if (step.orientation.folded() && step.summary.succeeded()) {
    step.summary.termination = Termination::Folded;
    step.summary.message = noted(step.summary.message, step.orientation.describe());
  }
}

}  // namespace fairshape
