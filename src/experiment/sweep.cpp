#include "experiment/sweep.h"

#include <cstdio>

#include "core/config.h"
#include "core/error.h"
#include "experiment/config_loader.h"

namespace fairshape {
namespace {

struct Axis {
  std::vector<std::string> keys;
  std::vector<std::vector<YAML::Node>> values;  // values[k][i]: key k at position i
  std::size_t size() const { return values.empty() ? 1 : values.front().size(); }
};

std::vector<YAML::Node> list_of(const YAML::Node& n, const std::string& key) {
  if (!n.IsSequence() || n.size() == 0)
    throw InvalidConfig("sweep." + key + ": expected a non-empty list of values, got '" + yaml_to_string(n) + "'");
  std::vector<YAML::Node> out;
  for (const auto& v : n) out.push_back(v);
  return out;
}

std::vector<Axis> axes_of(const YAML::Node& root) {
  std::vector<Axis> axes;
  const YAML::Node sweep = root["sweep"];
  if (!sweep) return axes;
  if (!sweep.IsMap()) throw InvalidConfig("sweep: expected a map of key: [values]");
  if (const YAML::Node zip = sweep["zip"]) {
    if (!zip.IsMap()) throw InvalidConfig("sweep.zip: expected a map of key: [values]");
    Axis a;
    for (const auto& kv : zip) {
      const std::string key = kv.first.as<std::string>();
      a.keys.push_back(key);
      a.values.push_back(list_of(kv.second, "zip." + key));
      if (a.values.back().size() != a.values.front().size())
        throw InvalidConfig("sweep.zip." + key + ": has " + std::to_string(a.values.back().size()) +
                            " values but sweep.zip." + a.keys.front() + " has " +
                            std::to_string(a.values.front().size()) + " (zipped lists must be equally long)");
    }
    if (!a.keys.empty()) axes.push_back(std::move(a));
  }
  for (const auto& kv : sweep) {
    const std::string key = kv.first.as<std::string>();
    if (key == "zip") continue;
    axes.push_back({{key}, {list_of(kv.second, key)}});
  }
  return axes;
}

}  // namespace

std::vector<std::string> swept_keys(const YAML::Node& root) {
  std::vector<std::string> keys;
  for (const auto& a : axes_of(root)) keys.insert(keys.end(), a.keys.begin(), a.keys.end());
  return keys;
}

std::string run_id_of(const YAML::Node& run_config) {
  YAML::Node c = YAML::Clone(run_config);
  c.remove("output");  // where results go does not change what is computed
  c.remove("name");
  c.remove("description");
  const std::string text = yaml_to_string(c);
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char ch : text) {
    h ^= ch;
    h *= 1099511628211ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::vector<RunPoint> expand_sweep(const YAML::Node& root) {
  const auto axes = axes_of(root);
  std::size_t total = 1;
  for (const auto& a : axes) total *= a.size();
  if (total > 1000000) throw InvalidConfig("sweep: expands to " + std::to_string(total) + " runs (limit 1e6)");
  YAML::Node base = YAML::Clone(root);
  base.remove("sweep");
  std::vector<RunPoint> runs;
  for (std::size_t flat = 0; flat < total; ++flat) {
    RunPoint p;
    p.index = static_cast<int>(flat);
    p.config = YAML::Clone(base);
    std::size_t rest = flat;
    // The last axis varies fastest, like nested loops written in config order.
    std::vector<std::size_t> pos(axes.size());
    for (std::size_t a = axes.size(); a-- > 0;) {
      pos[a] = rest % axes[a].size();
      rest /= axes[a].size();
    }
    for (std::size_t a = 0; a < axes.size(); ++a)
      for (std::size_t k = 0; k < axes[a].keys.size(); ++k) {
        const YAML::Node& v = axes[a].values[k][pos[a]];
        set_by_path(p.config, axes[a].keys[k], YAML::Clone(v));
        p.params.emplace_back(axes[a].keys[k], yaml_to_string(v));
      }
    p.run_id = run_id_of(p.config);
    runs.push_back(std::move(p));
  }
  return runs;
}

}  // namespace fairshape
