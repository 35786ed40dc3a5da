#include "fairshape/core/backend.h"

#include "fairshape/core/error.h"

namespace fairshape {

const NameTable<Backend>& backend_names() {
  static const NameTable<Backend> t{{Backend::Reference, "reference"}, {Backend::Optimized, "optimized"}};
  return t;
}

std::string_view to_string(Backend b) { return backend_names().name(b); }

Backend backend_from_string(std::string_view s) {
  const Backend b = backend_names().value(s, "implementation");
  require_backend(b);
  return b;
}

void require_backend(Backend b) {
  if (b == Backend::Optimized && !kOptimizedBackendBuilt)
    throw InvalidConfig("fairshape was built without TBB (FAIRSHAPE_WITH_TBB=OFF): only the reference back end exists");
}

}  // namespace fairshape
