#include "fairshape/core/error.h"
#include "fairshape/experiment/kinds/kinds.h"

namespace fairshape {

std::vector<std::unique_ptr<RunKind>> make_run_kinds() {
  std::vector<std::unique_ptr<RunKind>> kinds;
  kinds.push_back(make_surface_edit_kind());
  kinds.push_back(make_sheet_kind());
  kinds.push_back(make_curve_kind());
  kinds.push_back(make_feature_kind());
  return kinds;
}

RunKind& kind_of(const YAML::Node& run_config, const std::vector<std::unique_ptr<RunKind>>& kinds) {
  std::vector<RunKind*> owners;
  std::string markers;
  for (const auto& k : kinds) {
    if (k->owns(run_config)) owners.push_back(k.get());
    markers += (markers.empty() ? "" : "; ") + k->name() + ": " + k->marker();
  }
  if (owners.size() == 1) return *owners.front();
  if (owners.empty())
    throw InvalidConfig("the config is no run kind's (each kind is recognised by its key: " + markers + ")");
  std::string names;
  for (const RunKind* k : owners) names += (names.empty() ? "" : ", ") + k->name();
  throw InvalidConfig("the config has the keys of several run kinds (" + names + "; " + markers + ")");
}

}  // namespace fairshape
