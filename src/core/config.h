// Typed, strict access to one block of a YAML configuration.
//
// Every read names the key, its default and a doc string; the reads are the schema.
// check_no_unknown_keys() then rejects any key that was present but never read, so a typo
// fails with the list of valid keys instead of being silently ignored. The same reads,
// run on an empty block with a recorder attached, produce `fairshape list`'s option docs.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cmath>

#include <memory>
#include <optional>
#include <set>
#include <type_traits>
#include <string>
#include <vector>

#include "fairshape/core/error.h"
#include "fairshape/core/name_table.h"

namespace fairshape {

struct OptionDoc {
  std::string key, default_value, doc;
};

class Config {
 public:
  Config();  // an empty block
  Config(YAML::Node node, std::string path);

  const std::string& path() const { return path_; }  // "solver.sor"; "" at the root
  std::string key_path(const std::string& key) const;
  bool has(const std::string& key) const;
  const YAML::Node& node() const { return node_; }

  template <class T>
  T get(const std::string& key, const T& fallback, const std::string& doc);
  double get_number(const std::string& key, double fallback, double lo, double hi,
                    const std::string& doc);  // closed range [lo, hi]
  int get_int(const std::string& key, int fallback, int lo, int hi, const std::string& doc);
  std::string get_choice(const std::string& key, const std::string& fallback,
                         const std::vector<std::string>& choices, const std::string& doc);
  //! An enumeration spelled by `names`. \throw InvalidConfig naming the key and the valid names.
  template <class E>
  E get_enum(const std::string& key, E fallback, const NameTable<E>& names, const std::string& doc) {
    return names.value(get_choice(key, std::string(names.name(fallback)), names.names(), doc), key_path(key));
  }
  template <class T>
  T require(const std::string& key, const std::string& doc);

  // A nested map (empty if absent); its reads and unknown keys are tracked separately.
  Config child(const std::string& key, const std::string& doc);
  // A list of maps, e.g. `energy: [ {type: membrane}, ... ]`; a single map counts as a list.
  std::vector<Config> child_list(const std::string& key, const std::string& doc);

  void check_no_unknown_keys() const;  // throws InvalidConfig naming the key and valid keys
  //! Keys present in the block that no read has asked for (yet), in file order.
  std::vector<std::string> unread_keys() const;
  void set_recorder(std::shared_ptr<std::vector<OptionDoc>> r) { recorder_ = std::move(r); }
  //! True while `fairshape list` runs a factory on an empty block to collect its docs:
  //! factories skip checks that need a real value (required keys read as empty).
  bool documenting() const { return recorder_ != nullptr; }

 private:
  void mark(const std::string& key, const std::string& fallback, const std::string& doc);
  [[noreturn]] void type_error(const std::string& key, const std::string& expected) const;

  YAML::Node node_;
  std::string path_;
  std::shared_ptr<std::set<std::string>> read_keys_;
  std::shared_ptr<std::vector<OptionDoc>> recorder_;
};

std::string yaml_to_string(const YAML::Node& n);  // one-line flow style, for messages and CSV

std::string format_default(double v);  // shortest round-trip form, for docs

namespace config_detail {
// No config value of fairshape means anything as NaN or infinity: every number read is finite.
inline bool finite(double v) { return std::isfinite(v); }
template <class T>
bool finite(const T&) {
  return true;
}
template <class T>
bool finite(const std::vector<T>& v) {
  for (const auto& x : v)
    if (!finite(x)) return false;
  return true;
}
}  // namespace config_detail

template <class T>
T Config::get(const std::string& key, const T& fallback, const std::string& doc) {
  YAML::Node fb;
  fb = fallback;
  if constexpr (std::is_floating_point_v<T>) mark(key, format_default(fallback), doc);
  else mark(key, yaml_to_string(fb), doc);
  if (!has(key)) return fallback;
  T v;
  try {
    v = node_[key].as<T>();
  } catch (const YAML::Exception&) {
    type_error(key, yaml_to_string(fb).empty() ? "a value" : "a value like '" + yaml_to_string(fb) + "'");
  }
  if (!config_detail::finite(v)) type_error(key, "finite numbers");
  return v;
}

template <class T>
T Config::require(const std::string& key, const std::string& doc) {
  mark(key, "(required)", doc);
  if (!has(key)) {
    if (recorder_) return T{};
    throw InvalidConfig(key_path(key) + ": required key is missing (" + doc + ")");
  }
  T v;
  try {
    v = node_[key].as<T>();
  } catch (const YAML::Exception&) {
    type_error(key, doc);
  }
  if (!config_detail::finite(v)) type_error(key, "finite numbers");
  return v;
}

}  // namespace fairshape
