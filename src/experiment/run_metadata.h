// run.json: what produced a result folder (commit, compiler, flags, library versions, machine,
// threads, seed, times, the resolved config), so any number can be traced and reproduced.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include <yaml-cpp/yaml.h>

namespace fairshape {

nlohmann::json yaml_to_json(const YAML::Node& n);
nlohmann::json build_and_machine_info();  // git, compiler, flags, libraries, CPU, threads
std::string git_short_sha();             // 7 hex digits, or "nogit"
std::string utc_timestamp(const char* format = "%Y-%m-%dT%H:%M:%SZ");

}  // namespace fairshape
