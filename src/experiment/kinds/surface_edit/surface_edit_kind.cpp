// Boier-Martin et al.'s constrained edits of a (multiresolution) surface as a run kind.
#include "experiment/components.h"
#include "experiment/kinds/kinds.h"
#include "experiment/kinds/surface_edit/run_one.h"
#include "experiment/kinds/thread_limit.h"

namespace fairshape {
namespace {

class SurfaceEditKind final : public RunKind {
 public:
  std::string name() const override { return "surface_edit"; }
  std::string marker() const override { return "input.mesh without features"; }
  bool owns(const YAML::Node& c) const override {
    return c.IsMap() && c["input"] && c["input"].IsMap() && c["input"]["mesh"] && !c["features"] && !c["sheets"];
  }
  ValidatedRun validate(const YAML::Node& c, const std::vector<std::string>& dirs) const override {
    const SurfaceEditSpec spec = SurfaceEditSpec::from_config(c, components(), dirs);
    require_readable_mesh(spec.mesh_path, "input.mesh");
    return {spec.name, {spec.mesh_path}};
  }
  const std::vector<std::string>& metric_columns() const override { return fairshape::metric_columns(); }
  std::vector<TableSchema> tables() const override {
    return {{"iterations", iteration_columns()}, {"steps", step_columns()}};
  }
  MetricRow execute(const YAML::Node& c, const std::vector<std::string>& dirs, const RunOutputs& out) override {
    SurfaceEditSpec spec = SurfaceEditSpec::from_config(c, components(), dirs);
    const auto threads = limit_threads(spec.threads);
    MetricRow m = execute_run(spec, cache_, out);
    m["implementation"] = std::string(to_string(spec.implementation));
    // Where no linear solver runs (constraint_mode kkt, the interactive ladder, ...) the
    // column stays empty and unused_keys names solver.type if the config set it.
    m["solver.type"] = solver_is_used(spec) ? spec.solver_type : "";
    return m;
  }

 private:
  RunCache cache_;  // hierarchies and reference solutions shared by the runs of this process
};

}  // namespace

std::unique_ptr<RunKind> make_surface_edit_kind() { return std::make_unique<SurfaceEditKind>(); }

}  // namespace fairshape
