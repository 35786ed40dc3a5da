// Named factories for pluggable components (energies, constraints, solvers, ...).
//
// A name may have a reference and an optimized back end; both register under the same
// name. Registration is explicit (each module's register_*() function), never through
// static initialisers, which static libraries drop silently.
#pragma once

#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "fairshape/core/backend.h"
#include "fairshape/core/config.h"
#include "fairshape/core/error.h"

namespace fairshape {

template <class Base>
class Registry {
 public:
  using Factory = std::function<std::unique_ptr<Base>(Config&)>;
  struct Entry {
    std::string name;
    Backend backend;
    std::string doc;
    Factory make;
  };

  explicit Registry(std::string kind) : kind_(std::move(kind)) {}
  const std::string& kind() const { return kind_; }

  void add(const std::string& name, Backend backend, std::string doc, Factory make) {
    FAIRSHAPE_ASSERT(!has(name, backend), kind_ + " '" + name + "' registered twice");
    entries_.push_back({name, backend, std::move(doc), std::move(make)});
  }

  //! A name an entry had in an earlier release: using it is an error that names the new one.
  void add_former_name(const std::string& former, const std::string& current) {
    FAIRSHAPE_ASSERT(has(current), kind_ + " '" + current + "' must be registered before its former name");
    former_names_.emplace_back(former, current);
  }

  bool has(const std::string& name, Backend backend) const { return find(name, backend) != nullptr; }
  bool has(const std::string& name) const {
    return has(name, Backend::Reference) || has(name, Backend::Optimized);
  }

  // Builds the component from its options in `cfg`. The caller finishes with
  // cfg.check_no_unknown_keys(), after any other reads of the same block.
  std::unique_ptr<Base> create(const std::string& name, Backend backend, Config& cfg) const {
    require_backend(backend);  // a build without TBB registers no optimized back end
    const Entry* e = find(name, backend);
    if (!e) throw_unknown(name, backend);
    return e->make(cfg);
  }

  // The option docs of one entry: its factory run on an empty block with a recorder.
  std::vector<OptionDoc> options(const Entry& e) const {
    Config empty;
    auto rec = std::make_shared<std::vector<OptionDoc>>();
    empty.set_recorder(rec);
    e.make(empty);
    return *rec;
  }

  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& e : entries_)
      if (std::find(out.begin(), out.end(), e.name) == out.end()) out.push_back(e.name);
    return out;
  }
  const std::vector<Entry>& entries() const { return entries_; }

 private:
  const Entry* find(const std::string& name, Backend backend) const {
    for (const auto& e : entries_)
      if (e.name == name && e.backend == backend) return &e;
    return nullptr;
  }

  [[noreturn]] void throw_unknown(const std::string& name, Backend backend) const {
    for (const auto& [former, current] : former_names_)
      if (former == name) throw InvalidConfig(kind_ + " '" + name + "' is now called '" + current + "'");
    if (has(name)) {
      const Backend other = backend == Backend::Reference ? Backend::Optimized : Backend::Reference;
      throw InvalidConfig(kind_ + " '" + name + "' has no " + std::string(to_string(backend)) +
                          " back end (available: " + std::string(to_string(other)) + ")");
    }
    std::string known;
    for (const auto& n : names()) known += (known.empty() ? "" : ", ") + n;
    throw InvalidConfig("unknown " + kind_ + " '" + name + "' (known: " + known + ")");
  }

  std::string kind_;
  std::vector<Entry> entries_;
  std::vector<std::pair<std::string, std::string>> former_names_;
};

}  // namespace fairshape
