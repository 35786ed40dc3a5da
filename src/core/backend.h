// The two implementations every pluggable component may have.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "fairshape/core/name_table.h"

namespace fairshape {

enum class Backend { Reference, Optimized };

// FAIRSHAPE_WITH_TBB (1 or 0) comes with fairshape::core's compile definitions: the optimized
// back ends are TBB code, and a fairshape built without TBB has only the reference ones.
#ifndef FAIRSHAPE_WITH_TBB
#error "FAIRSHAPE_WITH_TBB is undefined: link fairshape::core (its compile definitions set it)"
#endif
inline constexpr bool kOptimizedBackendBuilt = FAIRSHAPE_WITH_TBB != 0;
//! For a step whose back end no caller chose: the optimized one where it is built.
inline constexpr Backend kFastestBackend = kOptimizedBackendBuilt ? Backend::Optimized : Backend::Reference;
//! \throw InvalidConfig for Backend::Optimized in a build without TBB, naming the cause (never
//! a silent fallback to the reference back end).
void require_backend(Backend b);
//! The back ends this build has: reference and optimized, or the reference alone without TBB.
inline std::vector<Backend> built_backends() {
  if (kOptimizedBackendBuilt) return {Backend::Reference, Backend::Optimized};
  return {Backend::Reference};
}

std::string_view to_string(Backend b);
Backend backend_from_string(std::string_view s);  // throws InvalidConfig listing the choices (and require_backend)
//! reference | optimized, as in `implementation:`.
const NameTable<Backend>& backend_names();

}  // namespace fairshape
