// Khodakovsky & Schröder's feature curves on Loop hierarchies as a run kind.
#include "experiment/kinds/feature/feature_run.h"
#include "experiment/kinds/kinds.h"
#include "experiment/kinds/thread_limit.h"

namespace fairshape {
namespace {

class FeatureKind final : public RunKind {
 public:
  std::string name() const override { return "feature"; }
  std::string marker() const override { return "features"; }
  bool owns(const YAML::Node& c) const override { return is_feature_config(c); }
  ValidatedRun validate(const YAML::Node& c, const std::vector<std::string>& dirs) const override {
    const FeatureRunSpec spec = FeatureRunSpec::from_config(c, dirs);
    require_readable_mesh(spec.mesh_path, "input.mesh");
    return {spec.name, {spec.mesh_path}};
  }
  const std::vector<std::string>& metric_columns() const override { return feature_metric_columns(); }
  std::vector<TableSchema> tables() const override { return {}; }
  std::vector<std::string> identity_columns() const override { return {"implementation"}; }  // no solver
  MetricRow execute(const YAML::Node& c, const std::vector<std::string>& dirs, const RunOutputs& out) override {
    FeatureRunSpec spec = FeatureRunSpec::from_config(c, dirs);
    const auto threads = limit_threads(spec.threads);
    return execute_feature_run(spec, out);
  }
};

}  // namespace

std::unique_ptr<RunKind> make_feature_kind() { return std::make_unique<FeatureKind>(); }

}  // namespace fairshape
