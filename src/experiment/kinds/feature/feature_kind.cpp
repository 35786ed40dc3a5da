// Khodakovsky & Schröder's feature curves on Loop hierarchies as a run kind.
#include <filesystem>
#include <map>

#include "fairshape/core/error.h"
#include "fairshape/experiment/kinds/feature/feature_exports.h"
#include "fairshape/experiment/kinds/feature/feature_run.h"
#include "fairshape/experiment/kinds/feature/feature_steps.h"
#include "fairshape/experiment/kinds/feature/sparse_run.h"
#include "fairshape/experiment/kinds/kinds.h"
#include "fairshape/experiment/kinds/thread_limit.h"

namespace fairshape {
namespace {

class FeatureKind final : public RunKind {
 public:
  std::string name() const override { return "feature"; }
  std::string marker() const override { return "features"; }
  bool owns(const YAML::Node& c) const override { return is_feature_config(c); }
  ValidatedRun validate(const YAML::Node& c, const std::vector<std::string>& dirs) override {
    FeatureRunSpec spec = FeatureRunSpec::from_config(c, dirs);
    // A saved hierarchy (.vtm) is read whole by check_on_hierarchy.
    if (std::filesystem::path(spec.mesh_path).extension() != ".vtm") require_readable_mesh(spec.mesh_path, "input.mesh");
    if (spec.adaptive_sparse) check_sparse(spec);
    else check_on_hierarchy(spec);
    return {spec.name, {spec.mesh_path}};
  }
  void validation_done() override { hierarchies_.clear(); }
  std::vector<OptionDoc> keys() const override { return FeatureRunSpec::keys(); }
  const std::vector<std::string>& metric_columns() const override { return feature_metric_columns(); }
  std::vector<TableSchema> tables() const override { return {feature_profile_table(), feature_attachment_table(), feature_step_table()}; }
  std::vector<std::string> identity_columns() const override { return {"implementation"}; }  // no solver
  MetricRow execute(const YAML::Node& c, const std::vector<std::string>& dirs, const RunOutputs& out) override {
    FeatureRunSpec spec = FeatureRunSpec::from_config(c, dirs);
    const auto threads = limit_threads(spec.threads);
    return execute_feature_run(spec, out);
  }

 private:
  // A sparse run is checked on its sparse levels: building the uniform hierarchy here would
  // cost what the run saves.
  static void check_sparse(FeatureRunSpec& spec) {
    try {
      check_sparse_features(spec);
    } catch (const Error& e) {
      throw InvalidConfig(std::string("features on ") + spec.mesh_path + ": " + e.what());
    }
  }

  // The features placed on the run's hierarchy and those of the coarsest feature level applied
  // (a point off the surface, a curve that leaves it, too curved a surface): the sweep is
  // refused before its first run. Finer features need the perturbed surface: the run checks them.
  void check_on_hierarchy(FeatureRunSpec& spec) {
    const std::string key = spec.mesh_path + "|" + std::to_string(spec.levels) + "|" + std::to_string(spec.remesh_base_faces) + "|" +
                            std::string(to_string(spec.loop_weights)) + "|" + std::string(to_string(spec.implementation));
    auto it = hierarchies_.find(key);
    try {
      if (it == hierarchies_.end()) it = hierarchies_.emplace(key, feature_hierarchy(spec)).first;
    } catch (const Error& e) {
      throw InvalidConfig("input.mesh: " + spec.mesh_path + ": " + e.what());
    }
    try {
      placed_features(spec, it->second)->check_coarsest_features();
    } catch (const Error& e) {
      throw InvalidConfig(std::string("features on ") + spec.mesh_path + ": " + e.what());
    }
  }

  std::map<std::string, MultiresSurface> hierarchies_;  // validation's, per mesh and depth
};

}  // namespace

std::unique_ptr<RunKind> make_feature_kind() { return std::make_unique<FeatureKind>(); }

}  // namespace fairshape
