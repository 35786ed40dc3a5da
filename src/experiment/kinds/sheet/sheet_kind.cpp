// Welch & Witkin's variational sheets as a run kind.
#include "fairshape/experiment/kinds/kinds.h"
#include "fairshape/experiment/kinds/sheet/sheet_files.h"
#include "fairshape/experiment/kinds/sheet/sheet_run.h"
#include "fairshape/experiment/kinds/thread_limit.h"

namespace fairshape {
namespace {

class SheetKind final : public RunKind {
 public:
  std::string name() const override { return "sheet"; }
  std::string marker() const override { return "sheets"; }
  bool owns(const YAML::Node& c) const override { return is_sheet_config(c); }
  ValidatedRun validate(const YAML::Node& c, const std::vector<std::string>& dirs) override {
    const SheetRunSpec spec = SheetRunSpec::from_config(c, dirs);
    return {spec.name, sheet_input_files(spec)};  // saved sheets (`file:`); the rest is the config
  }
  std::vector<OptionDoc> keys() const override { return SheetRunSpec::keys(); }
  const std::vector<std::string>& metric_columns() const override { return sheet_metric_columns(); }
  std::vector<TableSchema> tables() const override {
    return {{"steps", sheet_step_columns()}, {"cells", sheet_cell_columns()}};
  }
  MetricRow execute(const YAML::Node& c, const std::vector<std::string>& dirs, const RunOutputs& out) override {
    SheetRunSpec spec = SheetRunSpec::from_config(c, dirs);
    const auto threads = limit_threads(spec.threads);
    return execute_sheet_run(spec, out);
  }
};

}  // namespace

std::unique_ptr<RunKind> make_sheet_kind() { return std::make_unique<SheetKind>(); }

}  // namespace fairshape
