// Sauvage et al.'s length-preserving curve edits as a run kind.
#include "fairshape/core/error.h"
#include "fairshape/curve_design/editing_loop.h"
#include "fairshape/experiment/kinds/curve/curve_run.h"
#include "fairshape/experiment/kinds/kinds.h"
#include "fairshape/experiment/kinds/thread_limit.h"

namespace fairshape {
namespace {

class CurveKind final : public RunKind {
 public:
  std::string name() const override { return "curve"; }
  std::string marker() const override { return "input.curve"; }
  bool owns(const YAML::Node& c) const override { return is_curve_config(c); }
  ValidatedRun validate(const YAML::Node& c, const std::vector<std::string>& dirs) override {
    const CurveRunSpec spec = CurveRunSpec::from_config(c, dirs);
    // The first edit up to its solve (pins, closed-curve endpoints, an edit no curve of these
    // lengths can meet, zero-length segments); later edits start from the curve the earlier
    // ones make, so the run checks them.
    try {
      (void)prepare_editing_loop(spec.curve, spec.levels, spec.edits.front(), spec.settings.objective(),
                                 spec.implementation);
    } catch (const InvalidInput& e) {
      throw InvalidConfig("edits.0 on " + spec.curve_path + ": " + e.what());
    }
    return {spec.name, {spec.curve_path}};
  }
  std::vector<OptionDoc> keys() const override { return CurveRunSpec::keys(); }
  const std::vector<std::string>& metric_columns() const override { return curve_metric_columns(); }
  std::vector<TableSchema> tables() const override { return {{"steps", curve_step_columns()}, {"iterations", curve_iteration_columns()}}; }
  MetricRow execute(const YAML::Node& c, const std::vector<std::string>& dirs, const RunOutputs& out) override {
    CurveRunSpec spec = CurveRunSpec::from_config(c, dirs);
    const auto threads = limit_threads(spec.threads);
    return execute_curve_run(spec, out);
  }
};

}  // namespace

std::unique_ptr<RunKind> make_curve_kind() { return std::make_unique<CurveKind>(); }

}  // namespace fairshape
