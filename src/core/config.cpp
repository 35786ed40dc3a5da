#include "fairshape/core/config.h"

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

void Config::type_error(const std::string& key, const std::string& expected) const {
  throw InvalidConfig(key_path(key) + ": expected " + expected + ", got '" +
                      yaml_to_string(node_[key]) + "'");
}

double Config::get_number(const std::string& key, double fallback, double lo, double hi,
                          const std::string& doc) {
  const double v = get<double>(key, fallback, doc + " [" + yaml_to_string(YAML::Node(lo)) +
                                                  ", " + yaml_to_string(YAML::Node(hi)) + "]");
  if (!(v >= lo && v <= hi)) {  // also rejects NaN
    std::ostringstream os;
    os << key_path(key) << ": " << v << " is out of range [" << lo << ", " << hi << "]";
    throw InvalidConfig(os.str());
  }
  return v;
}

int Config::get_int(const std::string& key, int fallback, int lo, int hi, const std::string& doc) {
  const int v = get<int>(key, fallback, doc + " [" + std::to_string(lo) + ", " +
                                            std::to_string(hi) + "]");
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

Config Config::child(const std::string& key, const std::string& doc) {
  mark(key, "{}", doc);
  Config c(has(key) ? node_[key] : YAML::Node(YAML::NodeType::Map), key_path(key));
  c.recorder_ = recorder_;
  return c;
}

std::vector<Config> Config::child_list(const std::string& key, const std::string& doc) {
  mark(key, "[]", doc);
  std::vector<Config> out;
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
  for (auto& c : out) c.recorder_ = recorder_;
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

void Config::check_no_unknown_keys() const {
  for (const auto& kv : node_) {
    const std::string k = kv.first.as<std::string>();
    if (read_keys_->count(k)) continue;
    std::string valid;
    for (const auto& r : *read_keys_) valid += (valid.empty() ? "" : ", ") + r;
    throw InvalidConfig(key_path(k) + ": unknown key (valid keys here: " +
                        (valid.empty() ? "none" : valid) + ")");
  }
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
