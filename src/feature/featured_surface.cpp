#include "fairshape/feature/featured_surface.h"

namespace fairshape::feature {

FeaturedSurface::FeaturedSurface(MultiresSurface surface, Backend backend, ProfileTarget target)
    : original_(std::move(surface)), result_(original_), backend_(backend), target_(target) {
  if (original_.options().scheme != SchemeType::Loop)
    throw InvalidInput("feature curves live on Loop hierarchies; this one is " +
                       std::string(to_string(original_.options().scheme)));
}

int FeaturedSurface::add(FeatureCurve curve) {
  if (curve.level < 0 || curve.level > original_.levels())
    throw InvalidInput("feature '" + curve.name + "': level " + std::to_string(curve.level) +
                       " does not exist (the hierarchy has levels 0.." + std::to_string(original_.levels()) + ")");
  features_[next_id_] = std::move(curve);
  dirty_ = true;
  changed(next_id_);
  return next_id_++;
}

void FeaturedSurface::replace(int id, FeatureCurve curve) {
  if (!features_.count(id)) throw InvalidInput("no feature with id " + std::to_string(id));
  features_[id] = std::move(curve);
  dirty_ = true;
  changed(id);
}

void FeaturedSurface::remove(int id) {
  if (!features_.erase(id)) throw InvalidInput("no feature with id " + std::to_string(id));
  dirty_ = true;
  changed(id);
}

const MultiresSurface& FeaturedSurface::result() {
  if (dirty_) evaluate_or_update();
  return result_;
}

const LevelPerturbation& FeaturedSurface::perturbation(int level) {
  if (dirty_) evaluate_or_update();
  return perturbations_.at(static_cast<std::size_t>(level));
}

const std::map<int, BaseCurve>& FeaturedSurface::base_curves() {
  if (dirty_) evaluate_or_update();
  return base_curves_;
}

const std::vector<LevelOperator>& FeaturedSurface::operators() {
  if (dirty_) evaluate_or_update();
  return operators_;
}

const VisibleTargets& FeaturedSurface::visible_targets() {
  if (dirty_) evaluate_or_update();
  return visible_;
}

std::vector<int> FeaturedSurface::features_on(int level) const {
  std::vector<int> ids;
  for (const auto& [id, curve] : features_)
    if (curve.level == level) ids.push_back(id);
  return ids;
}

FeaturedSurface::LevelFeatures FeaturedSurface::apply_on(const SurfaceMesh& mesh, const std::vector<int>& ids) const {
  const TriangleSurface surface(mesh, loop_limit_normals(mesh));
  LevelFeatures out;
  for (int id : ids) out.curves.push_back(build_base_curve(surface, features_.at(id)));
  out.perturbation = compute_perturbation(surface, out.curves, backend_);
  return out;
}

void FeaturedSurface::check_coarsest_features() const {
  for (int level = 0; level <= original_.levels(); ++level)
    if (const std::vector<int> ids = features_on(level); !ids.empty()) {
      (void)apply_on(original_.mesh(level), ids);
      return;
    }
}

void FeaturedSurface::evaluate_or_update() {
  if (region_evaluation_ && evaluated_ && !original_changed_) {
    evaluate_region();
    return;
  }
  evaluate();
}

void FeaturedSurface::evaluate() {
  evaluated_ = false;  // until it has finished (a throw leaves the next evaluation whole)
  limit_fit_.resize(0, 3);
  limit_moving_.clear();
  result_ = original_;
  base_curves_.clear();
  operators_.clear();
  visible_ = {};
  perturbations_.assign(static_cast<std::size_t>(original_.levels() + 1), {});
  for (int level = 0; level <= original_.levels(); ++level) {
    const std::vector<int> ids = features_on(level);
    if (ids.empty()) continue;
    // The level as the curves were drawn on it: kept, since the finest level's displacement is
    // measured on it after the level itself has moved.
    LevelOperator op;
    op.level = level;
    op.ids = ids;
    op.mesh = std::make_shared<SurfaceMesh>(result_.mesh(level));
    op.surface = std::make_shared<TriangleSurface>(*op.mesh, loop_limit_normals(*op.mesh));
    for (int id : ids) op.curves.push_back(build_base_curve(*op.surface, features_.at(id)));
    LevelPerturbation& d = perturbations_[static_cast<std::size_t>(level)];
    d = compute_perturbation(*op.surface, op.curves, backend_);
    for (std::size_t k = 0; k < ids.size(); ++k) base_curves_[ids[k]] = op.curves[k];
    result_.set_level_positions(level, op.mesh->positions() + d.dense(op.mesh->n_vertices()));
    if (level < result_.levels()) result_.synthesize_from(level, DetailSpace::Local);
    operators_.push_back(std::move(op));
  }
  if (!operators_.empty()) {
    const int finest = original_.levels();
    visible_ = compose_visible_targets(original_.mesh(finest), original_.options(), operators_, backend_);
    if (target_ == ProfileTarget::Finest) result_.set_level_positions(finest, visible_.fine.back());
    if (target_ == ProfileTarget::Limit) {
      const MatrixX3 moved = visible_.limit.back() - visible_.limit.front();
      limit_fit_ = control_points_for_limit(original_.mesh(finest), visible_.limit_matrix, visible_.fine.front(), moved);
      limit_moving_.assign(static_cast<std::size_t>(moved.rows()), 0);
      for (int v = 0; v < static_cast<int>(moved.rows()); ++v) limit_moving_[static_cast<std::size_t>(v)] = moved.row(v).squaredNorm() > 0;
      result_.set_level_positions(finest, limit_fit_);
    }
  }
  report_ = {};
  for (int level = 0; level <= result_.levels(); ++level) report_.vertices_recomputed += result_.mesh(level).n_vertices();
  pending_.clear();
  original_changed_ = false;
  evaluated_ = true;
  dirty_ = false;
}

}  // namespace fairshape::feature
