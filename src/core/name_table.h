// Enumerations spelled in configs and on the command line: one table per enumeration gives
// both directions (the Ceres StringTo… idea), so a name is written once and an unknown name
// is refused with every valid one listed.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fairshape/core/error.h"

namespace fairshape {

template <class E>
class NameTable {
 public:
  NameTable(std::initializer_list<std::pair<E, const char*>> entries) : entries_(entries) {}

  std::string_view name(E v) const {
    for (const auto& [value, name] : entries_)
      if (value == v) return name;
    FAIRSHAPE_ASSERT(false, "an enumerator without a name");
    return "";
  }
  //! \throw InvalidConfig "<what>: unknown value '<name>' (valid: ...)".
  E value(std::string_view name, const std::string& what) const {
    for (const auto& [value, n] : entries_)
      if (name == n) return value;
    throw InvalidConfig(what + ": unknown value '" + std::string(name) + "' (valid: " + joined() + ")");
  }
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& e : entries_) out.emplace_back(e.second);
    return out;
  }
  std::string joined() const {
    std::string out;
    for (const auto& e : entries_) out += (out.empty() ? "" : ", ") + std::string(e.second);
    return out;
  }

 private:
  std::vector<std::pair<E, const char*>> entries_;
};

}  // namespace fairshape
