#include "fairshape/experiment/sweep.h"

#include <unordered_map>

#include "fairshape/core/config.h"
#include "fairshape/core/error.h"
#include "fairshape/experiment/sha256.h"
#include "fairshape/experiment/config_loader.h"

namespace fairshape {
namespace {

std::vector<YAML::Node> list_of(const YAML::Node& n, const std::string& key) {
  if (!n.IsSequence() || n.size() == 0)
    throw InvalidConfig("sweep." + key + ": expected a non-empty list of values, got '" + yaml_to_string(n) + "'");
  std::vector<YAML::Node> out;
  for (const auto& v : n) out.push_back(v);
  return out;
}

std::string key_of(const YAML::Node& k, const std::string& where) {
  if (!k.IsScalar()) throw InvalidConfig(where + ": a swept key must be a dotted key path, got '" + yaml_to_string(k) + "'");
  return k.as<std::string>();
}

}  // namespace

SweepSpace::SweepSpace(const YAML::Node& root) {
  // The base is the config without `sweep`: copied key by key, so a large sweep is not cloned
  // only to be removed again.
  base_ = YAML::Node(YAML::NodeType::Map);
  for (const auto& kv : root)
    if (kv.first.as<std::string>() != "sweep") base_[YAML::Clone(kv.first)] = YAML::Clone(kv.second);
  const YAML::Node sweep = root["sweep"];
  if (sweep) {
    if (!sweep.IsMap()) throw InvalidConfig("sweep: expected a map of key: [values]");
    if (const YAML::Node zip = sweep["zip"]) {
      if (!zip.IsMap()) throw InvalidConfig("sweep.zip: expected a map of key: [values]");
      Axis a;
      for (const auto& kv : zip) {
        const std::string key = key_of(kv.first, "sweep.zip");
        a.keys.push_back(key);
        a.values.push_back(list_of(kv.second, "zip." + key));
        if (a.values.back().size() != a.values.front().size())
          throw InvalidConfig("sweep.zip." + key + ": has " + std::to_string(a.values.back().size()) +
                              " values but sweep.zip." + a.keys.front() + " has " +
                              std::to_string(a.values.front().size()) + " (zipped lists must be equally long)");
      }
      if (!a.keys.empty()) axes_.push_back(std::move(a));
    }
    for (const auto& kv : sweep) {
      const std::string key = key_of(kv.first, "sweep");
      if (key == "zip") continue;
      axes_.push_back({{key}, {list_of(kv.second, key)}, {}, {}});
    }
  }
  for (Axis& a : axes_) {
    // Positions listing the same values make the same points: they are repeats of each other.
    std::vector<std::string> text(a.size());
    for (std::size_t i = 0; i < a.size(); ++i)
      for (const auto& column : a.values) text[i] += yaml_to_string(column[i]) + '\x1f';
    // Counted through a hash map, not by comparing every pair: an axis of 10,000 values took
    // 10^8 comparisons, in every shard of the sweep.
    std::unordered_map<std::string, std::size_t> seen;
    seen.reserve(a.size());
    a.occurrence.assign(a.size(), 0);
    a.multiplicity.assign(a.size(), 0);
    for (std::size_t i = 0; i < a.size(); ++i) a.occurrence[i] = seen[text[i]]++;
    for (std::size_t i = 0; i < a.size(); ++i) a.multiplicity[i] = seen[text[i]];
    if (a.size() > kMaxSweepPoints / size_)
      throw InvalidConfig("sweep: expands to more than " + std::to_string(kMaxSweepPoints) +
                          " runs (the limit); split it into several experiments or use --shard");
    size_ *= a.size();
  }
}

std::vector<std::string> SweepSpace::keys() const {
  std::vector<std::string> keys;
  for (const auto& a : axes_) keys.insert(keys.end(), a.keys.begin(), a.keys.end());
  return keys;
}

RunPoint SweepSpace::point(std::size_t index) const {
  FAIRSHAPE_ASSERT(index < size_, "sweep point out of range");
  RunPoint p;
  p.index = index;
  p.config = YAML::Clone(base_);
  // The last axis varies fastest, like nested loops written in config order.
  std::vector<std::size_t> pos(axes_.size());
  std::size_t rest = index;
  for (std::size_t a = axes_.size(); a-- > 0;) {
    pos[a] = rest % axes_[a].size();
    rest /= axes_[a].size();
  }
  // Identical points differ only in which duplicate position each axis took; in flat order
  // they come in the lexicographic order of those choices, a mixed-radix number.
  std::size_t repeat = 0;
  for (std::size_t a = 0; a < axes_.size(); ++a) {
    repeat = repeat * axes_[a].multiplicity[pos[a]] + axes_[a].occurrence[pos[a]];
    for (std::size_t k = 0; k < axes_[a].keys.size(); ++k) {
      const YAML::Node& v = axes_[a].values[k][pos[a]];
      set_by_path(p.config, axes_[a].keys[k], YAML::Clone(v));
      p.params.emplace_back(axes_[a].keys[k], yaml_to_string(v));
    }
  }
  p.run_id = run_id_of(p.config);
  if (repeat > 0) {
    p.run_id += '-';
    p.run_id.append(std::to_string(repeat + 1));
  }
  return p;
}

std::string run_id_of(const YAML::Node& run_config) {
  YAML::Node c = YAML::Clone(run_config);
  c.remove("sweep");
  return sha256_hex(yaml_to_string(c)).substr(0, 16);
}

std::vector<RunPoint> expand_sweep(const YAML::Node& root) {
  const SweepSpace space(root);
  std::vector<RunPoint> runs;
  for (std::size_t i = 0; i < space.size(); ++i) runs.push_back(space.point(i));
  return runs;
}

std::vector<std::string> swept_keys(const YAML::Node& root) { return SweepSpace(root).keys(); }

}  // namespace fairshape
