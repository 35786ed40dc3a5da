// What yaml-cpp's node API cannot tell once a file is loaded: a key written twice in one map
// (the last would silently win) and a key that is not a plain scalar (a list or a map as a
// key). Checked on the parser's events, with the lines of both places.
#pragma once

#include <string>

namespace fairshape {

//! \throw InvalidConfig "<file>:<line>: key 'k' repeats the key of line <l>" or
//! "<file>:<line>: a map key must be a plain value, not a list or a map".
void check_yaml_structure(const std::string& text, const std::string& file);

}  // namespace fairshape
