#include "fairshape/core/backend.h"

#include "fairshape/core/error.h"

namespace fairshape {

const NameTable<Backend>& backend_names() {
  static const NameTable<Backend> t{{Backend::Reference, "reference"}, {Backend::Optimized, "optimized"}};
  return t;
}

std::string_view to_string(Backend b) { return backend_names().name(b); }

Backend backend_from_string(std::string_view s) { return backend_names().value(s, "implementation"); }

}  // namespace fairshape
