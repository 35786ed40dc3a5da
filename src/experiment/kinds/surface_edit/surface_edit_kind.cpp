// Boier-Martin et al.'s constrained edits of a (multiresolution) surface as a run kind.
#include <filesystem>
#include <optional>
#include <set>

#include "fairshape/core/error.h"
#include "fairshape/design/regional_edit.h"
#include "fairshape/experiment/components.h"
#include "fairshape/experiment/kinds/kinds.h"
#include "fairshape/experiment/kinds/surface_edit/open_session.h"
#include "fairshape/experiment/kinds/surface_edit/run_one.h"
#include "fairshape/experiment/kinds/thread_limit.h"

namespace fairshape {
namespace {

class SurfaceEditKind final : public RunKind {
 public:
  std::string name() const override { return "surface_edit"; }
  std::string marker() const override { return "input.mesh without features"; }
  bool owns(const YAML::Node& c) const override {
    return c.IsMap() && c["input"] && c["input"].IsMap() && c["input"]["mesh"] && !c["features"] && !c["sheets"];
  }
  ValidatedRun validate(const YAML::Node& c, const std::vector<std::string>& dirs) override {
    const SurfaceEditSpec spec = SurfaceEditSpec::from_config(c, components(), dirs);
    // A saved hierarchy (.vtm) is read whole by check_on_hierarchy.
    if (std::filesystem::path(spec.mesh_path).extension() != ".vtm") require_readable_mesh(spec.mesh_path, "input.mesh");
    check_on_hierarchy(spec);
    return {spec.name, {spec.mesh_path}};
  }
  void validation_done() override {
    validation_cache_ = RunCache();
    checked_systems_.clear();
  }
  std::vector<OptionDoc> keys() const override { return SurfaceEditSpec::keys(); }
  const std::vector<std::string>& metric_columns() const override { return fairshape::metric_columns(); }
  std::vector<TableSchema> tables() const override {
    return {{"iterations", iteration_columns()}, {"steps", step_columns()}, {"setup", setup_columns()}};
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
  // The constraints placed and the energies checked on the run's hierarchy, H not assembled
  // (a conflict, a missing vertex, an empty selection, a curve off the surface, a valence
  // beyond the energy's limit): the sweep is refused before its first run.
  void check_on_hierarchy(const SurfaceEditSpec& spec) {
    if (!checked_systems_.insert(spec.system_key).second) return;  // points differing in the solver alone
    const MultiresSurface* rest = nullptr;
    try {
      rest = &validation_cache_.hierarchy(spec);
    } catch (const Error& e) {
      throw InvalidConfig("input.mesh: " + spec.mesh_path + ": " + e.what());
    }
    const int level = spec.edit_level < 0 ? rest->levels() : spec.edit_level;
    try {
      const EditTerms terms = spec.edit_terms();
      if (is_regional(terms)) {
        const std::optional<PassLadder> ladder =
            spec.accuracy.multilevel() ? std::optional<PassLadder>(pass_ladder(spec, spec.solver.get())) : std::nullopt;
        check_regional_edit(terms, *rest, level, *spec.solver, spec.constraint_mode, ladder ? &*ladder : nullptr);
      }
      else
        check_edit(terms, *rest, spec.accuracy.multilevel() ? spec.accuracy.coarse_level : level, level);
    } catch (const InvalidInput& e) {
      throw InvalidConfig(std::string("on ") + spec.mesh_path + ": " + e.what());
    }
  }

  RunCache cache_;             // hierarchies and reference solutions shared by the runs of this process
  RunCache validation_cache_;  // the hierarchies validation placed the constraints on
  std::set<std::string> checked_systems_;  // SurfaceEditSpec::system_key of the points checked
};

}  // namespace

std::unique_ptr<RunKind> make_surface_edit_kind() { return std::make_unique<SurfaceEditKind>(); }

}  // namespace fairshape
