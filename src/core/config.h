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

#include "fairshape/core/effective_options.h"
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
  // While documenting: one empty item, `key[]`, so the reads of an item are documented too.
  std::vector<Config> child_list(const std::string& key, const std::string& doc);

  //! Throws InvalidConfig naming every unknown key of this block with the valid ones (and the
  //! closest valid key when one is a likely misspelling). In a block of a parse_config() tree
  //! the keys are collected instead and the root's check throws them all together.
  void check_no_unknown_keys() const;
  //! "; `enrgy` in this block is not a key: a misspelling of `energy`?" when an unread key of
  //! the block is close to `key` (for errors about a missing key), else "".
  std::string misspelling_of(const std::string& key) const;
  //! Keys present in the block that no read has asked for (yet), in file order.
  std::vector<std::string> unread_keys() const;
  void set_recorder(std::shared_ptr<std::vector<OptionDoc>> r) { recorder_ = std::move(r); }
  //! True while `fairshape list` runs a factory on an empty block to collect its docs:
  //! factories skip checks that need a real value (required keys read as empty).
  bool documenting() const { return recorder_ != nullptr; }

 private:
  void mark(const std::string& key, const std::string& fallback, const std::string& doc);
  //! Under RecordEffectiveOptions: this read's key path and the value it returns.
  void record_effective(const std::string& key, const YAML::Node& value) const;
  [[noreturn]] void type_error(const std::string& key, const std::string& expected) const;

  std::vector<std::string> unknown_key_messages() const;
  Config adopt(Config c) const;  // c shares this tree's recorder and unknown-key collector

  YAML::Node node_;
  std::string path_;
  std::shared_ptr<std::set<std::string>> read_keys_;
  std::shared_ptr<std::vector<OptionDoc>> recorder_;
  //! parse_config(): the unknown keys of the tree's blocks, reported by the root.
  std::shared_ptr<std::vector<std::string>> unknown_keys_;
  bool collects_ = false;  // the root of a parse_config() tree

  template <class F>
  friend auto parse_config(const YAML::Node& node, F&& parse) -> decltype(parse(std::declval<Config&>()));
};

//! Parses a whole config with `parse(root)` and reports every unknown key of every block in one
//! error. The root's own check_no_unknown_keys() (which `parse` must call last) throws them all;
//! an error thrown before it (e.g. a required key missing because it was misspelt) gets the
//! unknown keys found so far added to its message.
//! Every key `parse` reads, with its default and doc: `parse` run on an empty root while
//! documenting (list items appear once, as `key[].item_key`). For `fairshape list --keys` and
//! `fairshape schema`; the parse must not need a real value while documenting.
template <class F>
std::vector<OptionDoc> document_keys(F&& parse) {
  Config root;
  auto recorded = std::make_shared<std::vector<OptionDoc>>();
  root.set_recorder(recorded);
  parse(root);
  return *recorded;
}

template <class F>
auto parse_config(const YAML::Node& node, F&& parse) -> decltype(parse(std::declval<Config&>())) {
  Config root(node, "");
  root.unknown_keys_ = std::make_shared<std::vector<std::string>>();
  root.collects_ = true;
  try {
    return parse(root);
  } catch (const InvalidConfig& e) {
    if (root.unknown_keys_->empty()) throw;
    std::string msg = e.what();
    for (const auto& u : *root.unknown_keys_) msg.append("\n  - also ").append(u);
    throw InvalidConfig(msg);
  }
}

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
  // The fallback is formatted only for the docs and for an error: a sweep validates every
  // point's config, and emitting YAML for each read was most of that time.
  const auto fallback_text = [&fallback] {
    YAML::Node fb;
    fb = fallback;
    return yaml_to_string(fb);
  };
  if (documenting()) {
    if constexpr (std::is_floating_point_v<T>) mark(key, format_default(fallback), doc);
    else mark(key, fallback_text(), doc);
  } else {
    read_keys_->insert(key);
  }
  if (!has(key)) {
    if (RecordEffectiveOptions::current() && !documenting()) {
      YAML::Node fb;
      fb = fallback;
      record_effective(key, fb);
    }
    return fallback;
  }
  T v;
  try {
    v = node_[key].as<T>();
  } catch (const YAML::Exception&) {
    const std::string fb = fallback_text();
    type_error(key, fb.empty() ? "a value" : "a value like '" + fb + "'");
  }
  if (!config_detail::finite(v)) type_error(key, "finite numbers");
  if (RecordEffectiveOptions::current()) record_effective(key, node_[key]);
  return v;
}

template <class T>
T Config::require(const std::string& key, const std::string& doc) {
  mark(key, "(required)", doc);
  if (!has(key)) {
    if (recorder_) return T{};
    throw InvalidConfig(key_path(key) + ": required key is missing (" + doc + ")" + misspelling_of(key));
  }
  T v;
  try {
    v = node_[key].as<T>();
  } catch (const YAML::Exception&) {
    type_error(key, doc);
  }
  if (!config_detail::finite(v)) type_error(key, "finite numbers");
  if (RecordEffectiveOptions::current()) record_effective(key, node_[key]);
  return v;
}

}  // namespace fairshape
