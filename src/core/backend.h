// The two implementations every pluggable component may have.
#pragma once

#include <string>
#include <string_view>

#include "fairshape/core/name_table.h"

namespace fairshape {

enum class Backend { Reference, Optimized };

std::string_view to_string(Backend b);
Backend backend_from_string(std::string_view s);  // throws InvalidConfig listing the choices
//! reference | optimized, as in `implementation:`.
const NameTable<Backend>& backend_names();

}  // namespace fairshape
