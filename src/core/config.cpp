#include "fairshape/core/config.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace fairshape {

Config::Config() : Config(YAML::Node(YAML::NodeType::Map), "") {}

Config::Config(YAML::Node node, std::string path)
    : node_(std::move(node)), path_(std::move(path)),
      read_keys_(std::make_shared<std::set<std::string>>()) {
  if (node_.IsNull() || !node_.IsDefined()) node_ = YAML::Node(YAML::NodeType::Map);
  if (!node_.IsMap()) {
    throw InvalidConfig((path_.empty() ? std::string("config") : path_) +
                        ": expected a map of keys, got '" + yaml_to_string(node_) + "'");
  }
}

std::string Config::key_path(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

bool Config::has(const std::string& key) const {
  const YAML::Node n = node_[key];
  return n.IsDefined() && !n.IsNull();
}

void Config::mark(const std::string& key, const std::string& fallback, const std::string& doc) {
  read_keys_->insert(key);
  if (recorder_) recorder_->push_back({key_path(key), fallback, doc});
}

void Config::record_effective(const std::string& key, const YAML::Node& value) const {
  // A clone: the recorded value must not change when the run's tree is edited afterwards.
  (*RecordEffectiveOptions::current())[key_path(key)] = YAML::Clone(value);
}

void Config::type_error(const std::string& key, const std::string& expected) const {
  throw InvalidConfig(key_path(key) + ": expected " + expected + ", got '" +
                      yaml_to_string(node_[key]) + "'");
}

double Config::get_number(const std::string& key, double fallback, double lo, double hi,
                          const std::string& doc) {
  const double v = get<double>(key, fallback, documenting() ? doc + " [" + yaml_to_string(YAML::Node(lo)) + ", " +
                                                                  yaml_to_string(YAML::Node(hi)) + "]"
                                                            : doc);
  if (!(v >= lo && v <= hi)) {  // also rejects NaN
    std::ostringstream os;
    os << key_path(key) << ": " << v << " is out of range [" << lo << ", " << hi << "]";
    throw InvalidConfig(os.str());
  }
  return v;
}

int Config::get_int(const std::string& key, int fallback, int lo, int hi, const std::string& doc) {
  const int v = get<int>(key, fallback,
                         documenting() ? doc + " [" + std::to_string(lo) + ", " + std::to_string(hi) + "]" : doc);
  if (v < lo || v > hi) {
    throw InvalidConfig(key_path(key) + ": " + std::to_string(v) + " is out of range [" +
                        std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return v;
}

std::string Config::get_choice(const std::string& key, const std::string& fallback,
                               const std::vector<std::string>& choices, const std::string& doc) {
  std::string all;
  for (const auto& c : choices) all += (all.empty() ? "" : ", ") + c;
  const std::string v = get<std::string>(key, fallback, doc + " (one of: " + all + ")");
  for (const auto& c : choices)
    if (c == v) return v;
  throw InvalidConfig(key_path(key) + ": unknown value '" + v + "' (valid: " + all + ")");
}

Config Config::adopt(Config c) const {
  c.recorder_ = recorder_;
  c.unknown_keys_ = unknown_keys_;
  return c;
}

Config Config::child(const std::string& key, const std::string& doc) {
  mark(key, "{}", doc);
  return adopt(Config(has(key) ? node_[key] : YAML::Node(YAML::NodeType::Map), key_path(key)));
}

std::vector<Config> Config::child_list(const std::string& key, const std::string& doc) {
  mark(key, "[]", doc);
  std::vector<Config> out;
  if (documenting() && !has(key)) return {adopt(Config(YAML::Node(YAML::NodeType::Map), key_path(key) + "[]"))};
  if (!has(key)) return out;
  const YAML::Node n = node_[key];
  if (n.IsMap()) {
    out.emplace_back(n, key_path(key));
  } else if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i)
      out.emplace_back(n[i], key_path(key) + "[" + std::to_string(i) + "]");
  } else {
    type_error(key, "a list of maps");
  }
  for (auto& c : out) c = adopt(std::move(c));
  return out;
}

std::vector<std::string> Config::unread_keys() const {
  std::vector<std::string> out;
  for (const auto& kv : node_) {
    const std::string k = kv.first.as<std::string>();
    if (!read_keys_->count(k)) out.push_back(k);
  }
  return out;
}

namespace {

// Levenshtein distance, for "did you mean": config keys are short.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// A likely misspelling: a few edits apart, relative to the length (`type` is not `size`), or
// another ending of the same word (`energies` for `energy`).
bool close_to(const std::string& typed, const std::string& key) {
  if (typed == key) return false;
  const std::size_t shorter = std::min(typed.size(), key.size());
  std::size_t prefix = 0;
  while (prefix < shorter && typed[prefix] == key[prefix]) ++prefix;
  if (prefix >= std::max<std::size_t>(4, shorter - std::min<std::size_t>(shorter, 2))) return true;
  return edit_distance(typed, key) <= std::max<std::size_t>(1, shorter / 3);
}

}  // namespace

std::vector<std::string> Config::unknown_key_messages() const {
  std::vector<std::string> out;
  bool any = false;
  for (const auto& kv : node_) any |= !read_keys_->count(kv.first.as<std::string>());
  if (!any) return out;
  std::vector<std::string> valid(read_keys_->begin(), read_keys_->end());
  // Keys the config loader and the sweep consume before a run's blocks are read.
  if (path_.empty() && collects_)
    for (const char* k : {"defaults", "smoke", "sweep"}) valid.emplace_back(k);
  std::sort(valid.begin(), valid.end());
  std::string listed;
  for (const auto& r : valid) listed += (listed.empty() ? "" : ", ") + r;
  for (const auto& kv : node_) {
    const std::string k = kv.first.as<std::string>();
    if (read_keys_->count(k)) continue;
    std::string msg = key_path(k) + ": unknown key (";
    for (const auto& r : valid)
      if (close_to(k, r)) {
        msg += "did you mean " + key_path(r) + "? ";
        break;
      }
    out.push_back(msg + "valid keys here: " + (listed.empty() ? "none" : listed) + ")");
  }
  return out;
}

void Config::check_no_unknown_keys() const {
  std::vector<std::string> found = unknown_key_messages();
  if (unknown_keys_ && !collects_) {  // a block of a parse_config() tree: its root reports
    unknown_keys_->insert(unknown_keys_->end(), found.begin(), found.end());
    return;
  }
  if (collects_) {  // reported here, so parse_config() does not add them to this error again
    found.insert(found.begin(), unknown_keys_->begin(), unknown_keys_->end());
    unknown_keys_->clear();
  }
  if (found.empty()) return;
  if (found.size() == 1) throw InvalidConfig(found.front());
  std::string msg = std::to_string(found.size()) + " unknown keys:";
  for (const auto& f : found) msg.append("\n  - ").append(f);
  throw InvalidConfig(msg);
}

std::string Config::misspelling_of(const std::string& key) const {
  for (const auto& kv : node_) {
    const std::string k = kv.first.as<std::string>();
    if (!read_keys_->count(k) && close_to(k, key))
      return "; `" + key_path(k) + "` in the config is not a key: a misspelling of `" + key_path(key) + "`?";
  }
  return "";
}

std::string format_default(double v) {
  char buf[32];
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

std::string yaml_to_string(const YAML::Node& n) {
  if (!n.IsDefined() || n.IsNull()) return "";
  if (n.IsScalar()) return n.Scalar();
  YAML::Emitter e;
  e.SetMapFormat(YAML::Flow);
  e.SetSeqFormat(YAML::Flow);
  e << n;
  return e.c_str();
}

}  // namespace fairshape
