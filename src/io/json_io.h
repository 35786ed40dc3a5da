// JSON output through nlohmann::json, written atomically.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace fairshape {

void write_json(const nlohmann::json& j, const std::string& path);
nlohmann::json read_json(const std::string& path);  // throws ParseError

}  // namespace fairshape
