// Expands `sweep:` into runs: a Cartesian product over its keys, where `zip:` lists of equal
// length count as one axis. Each run is the base config with the swept values set.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace fairshape {

struct RunPoint {
  int index = 0;                                            // position in the full sweep
  std::vector<std::pair<std::string, std::string>> params;  // swept key -> value, for the CSV
  YAML::Node config;                                        // resolved, without `sweep`
  std::string run_id;                                       // hash of the resolved config
};

//! Swept keys in CSV column order (zip keys in their order, then the others).
std::vector<std::string> swept_keys(const YAML::Node& root);
//! \throw InvalidConfig for a non-list value, an empty list or zip lists of unequal length.
std::vector<RunPoint> expand_sweep(const YAML::Node& root);
//! 16 hex digits of a 64-bit FNV-1a hash of the run's canonical YAML (output settings excluded).
std::string run_id_of(const YAML::Node& run_config);

}  // namespace fairshape
