#include "fairshape/feature/feature_session.h"

#include <utility>

#include "fairshape/core/error.h"
#include "fairshape/core/timer.h"

namespace fairshape {

FeatureEdit FeatureEdit::add(feature::FeatureDrawing d) {
  FeatureEdit e;
  e.drawing = std::move(d);
  return e;
}

FeatureEdit FeatureEdit::replace(int id, feature::FeatureDrawing d) {
  FeatureEdit e;
  e.kind = Kind::Replace, e.id = id, e.drawing = std::move(d);
  return e;
}

FeatureEdit FeatureEdit::set_params(int id, const feature::FeatureParams& q) {
  FeatureEdit e;
  e.kind = Kind::SetParams, e.id = id, e.params = q;
  return e;
}

FeatureEdit FeatureEdit::remove(int id) {
  FeatureEdit e;
  e.kind = Kind::Remove, e.id = id;
  return e;
}

FeatureSession::FeatureSession(MultiresSurface original, const FeatureSessionOptions& options)
    : surface_(std::move(original), options.backend, options.profile_target) {
  surface_.set_region_evaluation(options.region_steps);
}

MultiresSurface& FeatureSession::edit_original() {
  changed_ = true;
  drawn_on_.clear();
  diagonal_.reset();
  rest_faces_.reset();
  return surface_.original();
}

const feature::TriangleSurface& FeatureSession::drawn_on(int level) {
  if (const auto it = drawn_on_.find(level); it != drawn_on_.end()) return it->second;
  const SurfaceMesh& mesh = std::as_const(surface_).original().mesh(level);
  return drawn_on_.try_emplace(level, mesh, feature::loop_limit_normals(mesh)).first->second;  // O(level): once
}

double FeatureSession::diagonal() {
  if (!diagonal_) {
    const MatrixX3& p = std::as_const(surface_).original().mesh(levels()).positions();
    diagonal_ = (p.colwise().maxCoeff() - p.colwise().minCoeff()).norm();
  }
  return *diagonal_;
}

const RestFaces& FeatureSession::rest_faces() {
  if (!rest_faces_) rest_faces_.emplace(std::as_const(surface_).original().mesh(levels()));
  return *rest_faces_;
}

// Placed on the level of the surface without features, as the paper draws a curve (§1.4); its
// faces and width checked before anything changes.
void FeatureSession::place(feature::FeatureDrawing& f, FeatureStep& step) {
  const MultiresSurface& o = std::as_const(surface_).original();
  const int level = f.curve.level;
  if (level < 0 || level > o.levels())
    throw InvalidInput("feature '" + f.curve.name + "': level " + std::to_string(level) +
                       " does not exist (the hierarchy has levels 0.." + std::to_string(o.levels()) + ")");
  f.curve.params.validate(f.key.empty() ? "feature '" + f.curve.name + "'" : f.key);
  const double diag = diagonal();
  FeaturePlacement p;
  p.name = f.curve.name, p.level = level, p.allowed = f.max_distance * diag;
  if (!f.world_points.empty() || f.placement) {
    const feature::TriangleSurface& s = drawn_on(level);
    feature::place_on_level(s, diag, f);
    p.farthest = feature::farthest_placed_point(s, f);
  }
  for (const auto& q : f.curve.points)
    if (q.face < 0 || q.face >= o.mesh(level).n_faces())
      throw InvalidInput("feature '" + f.curve.name + "': face " + std::to_string(q.face) + " is not a face of level " +
                         std::to_string(level));
  feature::check_feature_width(f, f.curve.params, o.mesh(0), o.levels());
  p.points = static_cast<int>(f.curve.points.size());
  step.placed.push_back(std::move(p));
}

int FeatureSession::stage_add(feature::FeatureDrawing f) {
  FeatureStep placed;
  place(f, placed);
  const int id = surface_.add(std::move(f.curve));
  placed.placed.back().id = id;
  staged_.placed.push_back(std::move(placed.placed.back()));
  staged_.added.push_back(id);
  changed_ = true;
  return id;
}

FeatureStep FeatureSession::apply(std::vector<FeatureEdit> edits, FeatureChecks checks) {
  FeatureStep step;
  const Timer place_timer;
  // Everything that can be refused is refused before the surface changes.
  std::vector<std::size_t> placement_of(edits.size(), 0);
  for (std::size_t i = 0; i < edits.size(); ++i) {
    FeatureEdit& e = edits[i];
    if (e.kind != FeatureEdit::Kind::Add && !features().count(e.id))
      throw InvalidInput("no feature with id " + std::to_string(e.id));
    if (e.kind == FeatureEdit::Kind::Add || e.kind == FeatureEdit::Kind::Replace) {
      placement_of[i] = step.placed.size();
      place(e.drawing, step);
    } else if (e.kind == FeatureEdit::Kind::SetParams) {
      feature::FeatureDrawing now;
      now.curve = features().at(e.id);
      now.key = "feature '" + now.curve.name + "'";
      e.params.validate(now.key);
      feature::check_feature_width(now, e.params, std::as_const(surface_).original().mesh(0), levels());
    }
  }
  step.place_s = place_timer.seconds();
  for (std::size_t i = 0; i < edits.size(); ++i) {
    FeatureEdit& e = edits[i];
    switch (e.kind) {
      case FeatureEdit::Kind::Add:
        e.id = surface_.add(std::move(e.drawing.curve));
        step.placed[placement_of[i]].id = e.id;
        step.added.push_back(e.id);
        break;
      case FeatureEdit::Kind::Replace:
        surface_.replace(e.id, std::move(e.drawing.curve));
        step.placed[placement_of[i]].id = e.id;
        step.moved.push_back(e.id);
        break;
      case FeatureEdit::Kind::SetParams: {
        feature::FeatureCurve c = features().at(e.id);
        c.params = e.params;
        surface_.replace(e.id, std::move(c));
        step.changed.push_back(e.id);
        break;
      }
      case FeatureEdit::Kind::Remove:
        surface_.remove(e.id);
        step.removed.push_back(e.id);
        break;
    }
  }
  // What stage_add placed since the last step is this step's too.
  step.added.insert(step.added.begin(), staged_.added.begin(), staged_.added.end());
  step.placed.insert(step.placed.begin(), staged_.placed.begin(), staged_.placed.end());
  staged_ = {};
  changed_ = changed_ || !edits.empty();
  const Timer solve_timer;
  (void)surface_.result();
  step.solve_s = solve_timer.seconds();
  // A step with nothing to apply recomputes nothing (the surface keeps its last evaluation).
  if (changed_) step.evaluation = surface_.last_evaluation();
  else step.evaluation.region = true, step.evaluation.vertices.assign(static_cast<std::size_t>(levels() + 1), {});
  changed_ = false;
  check_step(step, checks);
  return step;
}

FeatureStep FeatureSession::add(feature::FeatureDrawing f, FeatureChecks checks) {
  return apply({FeatureEdit::add(std::move(f))}, checks);
}
FeatureStep FeatureSession::replace(int id, feature::FeatureDrawing f, FeatureChecks checks) {
  return apply({FeatureEdit::replace(id, std::move(f))}, checks);
}
FeatureStep FeatureSession::set_params(int id, const feature::FeatureParams& q, FeatureChecks checks) {
  return apply({FeatureEdit::set_params(id, q)}, checks);
}
FeatureStep FeatureSession::remove(int id, FeatureChecks checks) { return apply({FeatureEdit::remove(id)}, checks); }
FeatureStep FeatureSession::evaluate(FeatureChecks checks) { return apply({}, checks); }

// Measured on the result: what the step moved (only the recomputed rows can have moved: every
// other vertex keeps its value bit for bit, featured_surface.h) and the finest faces turned over.
void FeatureSession::check_step(FeatureStep& step, FeatureChecks checks) {
  const Timer timer;
  const MultiresSurface& result = surface_.result();
  step.surface = &result;
  const MatrixX3& now = result.mesh(levels()).positions();
  const double diag = (now.colwise().maxCoeff() - now.colwise().minCoeff()).norm();
  if (previous_.rows() != now.rows()) {
    previous_ = now;
  } else if (step.evaluation.region) {
    step.vertices_changed = 0;
    for (int v : step.evaluation.vertices[static_cast<std::size_t>(levels())]) {
      const double d = (now.row(v) - previous_.row(v)).norm();
      step.max_change = std::max(step.max_change, d);
      step.vertices_changed += d > 1e-12 * diag ? 1 : 0;
      previous_.row(v) = now.row(v);
    }
  } else {
    const Eigen::VectorXd change = (now - previous_).rowwise().norm();
    step.vertices_changed = (change.array() > 1e-12 * diag).count();
    step.max_change = change.size() ? change.maxCoeff() : 0.0;
    previous_ = now;
  }
  step.folds = rest_faces().compare(now);
  step.summary.termination = Termination::Converged;
  if (!step.folds.flipped.empty()) {
    step.summary.termination = Termination::Folded;
    step.summary.message = "folded: " + step.folds.describe();
  }
  if (checks == FeatureChecks::Profiles) {
    step.profiles = measure();
    step.summary = step.profiles->summary;
  }
  step.check_s = timer.seconds();
}

FeatureMeasurement FeatureSession::measure() {
  const Timer timer;
  FeatureMeasurement m;
  m.features = feature::measure_features(surface_);
  std::size_t within = 0;
  std::string first_miss;
  for (const feature::FeatureMeasure& f : m.features) {
    within += f.within_tolerance ? 1 : 0;
    if (!f.within_tolerance && first_miss.empty())
      first_miss = "feature '" + f.name + "' (level " + std::to_string(f.level) + "), " + f.why;
  }
  m.summary.termination = Termination::Converged;
  if (!first_miss.empty()) {
    m.summary.termination = Termination::ConstraintsUnmet;
    m.summary.message = std::to_string(m.features.size() - within) + " of " + std::to_string(m.features.size()) +
                        " features miss their tolerance; first: " + first_miss;
  }
  // A fold outranks a profile miss: the surface is wrong before its profile is (README, "Folds").
  m.folds = rest_faces().compare(surface_.result().mesh(levels()).positions());
  if (!m.folds.flipped.empty()) {
    const std::string miss = m.summary.termination == Termination::ConstraintsUnmet ? "; " + m.summary.message : "";
    m.summary.termination = Termination::Folded;
    m.summary.message = "folded: " + m.folds.describe() + miss;
  }
  m.check_s = timer.seconds();
  return m;
}

}  // namespace fairshape
