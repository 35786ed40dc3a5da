#include "core/backend.h"

#include "core/error.h"

namespace fairshape {

std::string_view to_string(Backend b) {
  return b == Backend::Reference ? "reference" : "optimized";
}

Backend backend_from_string(std::string_view s) {
  if (s == "reference") return Backend::Reference;
  if (s == "optimized") return Backend::Optimized;
  throw InvalidConfig("unknown backend '" + std::string(s) + "' (valid: reference, optimized)");
}

}  // namespace fairshape
