#include "feature/featured_surface.h"

namespace fairshape::feature {

FeaturedSurface::FeaturedSurface(MultiresSurface surface, Backend backend)
    : original_(std::move(surface)), result_(original_), backend_(backend) {
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
  return next_id_++;
}

void FeaturedSurface::replace(int id, FeatureCurve curve) {
  if (!features_.count(id)) throw InvalidInput("no feature with id " + std::to_string(id));
  features_[id] = std::move(curve);
  dirty_ = true;
}

void FeaturedSurface::remove(int id) {
  if (!features_.erase(id)) throw InvalidInput("no feature with id " + std::to_string(id));
  dirty_ = true;
}

const MultiresSurface& FeaturedSurface::result() {
  if (dirty_) evaluate();
  return result_;
}

const LevelPerturbation& FeaturedSurface::perturbation(int level) {
  if (dirty_) evaluate();
  return perturbations_.at(static_cast<std::size_t>(level));
}

const std::map<int, BaseCurve>& FeaturedSurface::base_curves() {
  if (dirty_) evaluate();
  return base_curves_;
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

void FeaturedSurface::evaluate() {
  result_ = original_;
  base_curves_.clear();
  perturbations_.assign(static_cast<std::size_t>(original_.levels() + 1), {});
  for (int level = 0; level <= original_.levels(); ++level) {
    const std::vector<int> ids = features_on(level);
    if (ids.empty()) continue;
    const SurfaceMesh& mesh = result_.mesh(level);
    LevelFeatures applied = apply_on(mesh, ids);
    for (std::size_t k = 0; k < ids.size(); ++k) base_curves_[ids[k]] = std::move(applied.curves[k]);
    LevelPerturbation& d = perturbations_[static_cast<std::size_t>(level)];
    d = std::move(applied.perturbation);
    result_.set_level_positions(level, mesh.positions() + d.dense(mesh.n_vertices()));
    if (level < result_.levels()) result_.synthesize_from(level, DetailSpace::Local);
  }
  dirty_ = false;
}

}  // namespace fairshape::feature
