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

// A value's text inside a flow collection, as the one-line emission of a whole config holds it.
std::string flow_text(const YAML::Node& v) {
  // A clone: putting v itself into another node would merge their yaml-cpp memory pools, and
  // every later use of any swept value would then walk the pool of all of them.
  YAML::Node seq(YAML::NodeType::Sequence);
  seq.push_back(YAML::Clone(v));
  const std::string s = yaml_to_string(seq);  // "[...]"
  return s.substr(1, s.size() - 2);
}

constexpr const char* kSlot = "fairshape_swept_value_slot_";

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
      axes_.push_back({{key}, {list_of(kv.second, key)}, {}, {}, {}, {}});
    }
  }
  for (Axis& a : axes_) {
    for (const auto& column : a.values) {
      a.text.emplace_back();
      a.flow.emplace_back();
      for (const YAML::Node& v : column) {
        a.text.back().push_back(yaml_to_string(v));
        a.flow.back().push_back(flow_text(v));
      }
    }
    // Positions listing the same values make the same points: they are repeats of each other.
    std::vector<std::string> text(a.size());
    for (std::size_t i = 0; i < a.size(); ++i)
      for (const auto& column : a.text) text[i] += column[i] + '\x1f';
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
  prepare_hash_text();
}

void SweepSpace::prepare_hash_text() {
  if (axes_.empty()) return;
  YAML::Node slotted = YAML::Clone(base_);
  std::vector<std::pair<std::size_t, std::size_t>> slots;
  for (std::size_t a = 0; a < axes_.size(); ++a)
    for (std::size_t k = 0; k < axes_[a].keys.size(); ++k) {
      set_by_path(slotted, axes_[a].keys[k], YAML::Node(kSlot + std::to_string(slots.size()) + "_"));
      slots.emplace_back(a, k);
    }
  const std::string text = yaml_to_string(slotted);
  std::vector<std::string> pieces;
  std::vector<std::pair<std::size_t, std::size_t>> order;
  std::size_t from = 0;
  for (std::size_t at = text.find(kSlot); at != std::string::npos; at = text.find(kSlot, from)) {
    pieces.push_back(text.substr(from, at - from));
    const std::size_t number = at + std::char_traits<char>::length(kSlot), end = text.find('_', number);
    const std::string digits = text.substr(number, end == std::string::npos ? std::string::npos : end - number);
    // The marker's text in the config itself (not ours): emit per point.
    if (end == std::string::npos || digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos ||
        std::stoul(digits) >= slots.size())
      return;
    order.push_back(slots[std::stoul(digits)]);
    from = end + 1;
  }
  pieces.push_back(text.substr(from));
  if (order.size() != slots.size()) return;  // a swept key inside another's value: emit per point
  hash_pieces_ = std::move(pieces);
  hash_slots_ = std::move(order);
  // Each value's text in a map as in a sequence, and whole points with every axis at its first
  // and at its last position, as run_id_of emits them.
  for (const Axis& a : axes_)
    for (const auto& column : a.values)
      for (const YAML::Node& v : column) {
        YAML::Node map(YAML::NodeType::Map);
        map["k"] = YAML::Clone(v);
        if (yaml_to_string(map) != "{k: " + flow_text(v) + "}") return hash_pieces_.clear();
      }
  std::vector<std::size_t> first(axes_.size(), 0), last(axes_.size());
  for (std::size_t a = 0; a < axes_.size(); ++a) last[a] = axes_[a].size() - 1;
  for (const auto& pos : {first, last})
    if (hash_text(pos) != yaml_to_string(config_at(pos))) return hash_pieces_.clear();
}

std::vector<std::size_t> SweepSpace::positions(std::size_t index) const {
  // The last axis varies fastest, like nested loops written in config order.
  std::vector<std::size_t> pos(axes_.size());
  std::size_t rest = index;
  for (std::size_t a = axes_.size(); a-- > 0;) {
    pos[a] = rest % axes_[a].size();
    rest /= axes_[a].size();
  }
  return pos;
}

YAML::Node SweepSpace::config_at(const std::vector<std::size_t>& pos) const {
  YAML::Node config = YAML::Clone(base_);
  for (std::size_t a = 0; a < axes_.size(); ++a)
    for (std::size_t k = 0; k < axes_[a].keys.size(); ++k)
      set_by_path(config, axes_[a].keys[k], YAML::Clone(axes_[a].values[k][pos[a]]));
  return config;
}

std::string SweepSpace::hash_text(const std::vector<std::size_t>& pos) const {
  std::string text = hash_pieces_.front();
  for (std::size_t s = 0; s < hash_slots_.size(); ++s) {
    const auto [a, k] = hash_slots_[s];
    text.append(axes_[a].flow[k][pos[a]]).append(hash_pieces_[s + 1]);
  }
  return text;
}

std::string SweepSpace::run_id(std::size_t index) const {
  FAIRSHAPE_ASSERT(index < size_, "sweep point out of range");
  const std::vector<std::size_t> pos = positions(index);
  return run_id_at(pos, hash_pieces_.empty() ? run_id_of(config_at(pos)) : sha256_hex(hash_text(pos)).substr(0, 16));
}

std::string SweepSpace::run_id_at(const std::vector<std::size_t>& pos, std::string id) const {
  // Identical points differ only in which duplicate position each axis took; in flat order
  // they come in the lexicographic order of those choices, a mixed-radix number.
  std::size_t repeat = 0;
  for (std::size_t a = 0; a < axes_.size(); ++a)
    repeat = repeat * axes_[a].multiplicity[pos[a]] + axes_[a].occurrence[pos[a]];
  if (repeat > 0) id.append("-").append(std::to_string(repeat + 1));
  return id;
}

std::vector<std::string> SweepSpace::keys() const {
  std::vector<std::string> keys;
  for (const auto& a : axes_) keys.insert(keys.end(), a.keys.begin(), a.keys.end());
  return keys;
}

std::vector<std::pair<std::string, std::string>> SweepSpace::params(std::size_t index) const {
  const std::vector<std::size_t> pos = positions(index);
  std::vector<std::pair<std::string, std::string>> out;
  for (std::size_t a = 0; a < axes_.size(); ++a)
    for (std::size_t k = 0; k < axes_[a].keys.size(); ++k) out.emplace_back(axes_[a].keys[k], axes_[a].text[k][pos[a]]);
  return out;
}

RunPoint SweepSpace::point(std::size_t index) const {
  FAIRSHAPE_ASSERT(index < size_, "sweep point out of range");
  RunPoint p;
  p.index = index;
  const std::vector<std::size_t> pos = positions(index);
  p.config = config_at(pos);
  p.params = params(index);
  p.run_id = run_id_at(pos, hash_pieces_.empty() ? run_id_of(p.config) : sha256_hex(hash_text(pos)).substr(0, 16));
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
