// What yaml-cpp's node API cannot tell once a file is loaded: a key written twice in one map
// (the last would silently win) and a key that is not a plain scalar (a list or a map as a
// key). Checked on the parser's events, with the lines of both places.
#pragma once

#include <string>
#include <string_view>

namespace fairshape {

//! \throw InvalidConfig "<file>:<line>: key 'k' repeats the key of line <l>",
//! "<file>:<line>: a map key must be a plain value, not a list or a map", for bytes that are not
//! UTF-8 (check_utf8) and for a second YAML document.
void check_yaml_structure(const std::string& text, const std::string& file);
//! \throw InvalidConfig "<file>:<line>: byte 0xE9 at column <c> is not UTF-8 …".
void check_utf8(std::string_view text, const std::string& file);

}  // namespace fairshape
