// Experiment files: YAML with `defaults: [other.yaml, ...]` merged underneath (paths relative
// to the including file), then `--set key.path=value` overrides (value parsed as YAML, so
// `--set 'sweep.input.levels=[4]'` replaces a whole list).
#pragma once

#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace fairshape {

//! Full: the experiment as written. Smoke: its CI-sized variant — the file's `smoke:` block,
//! a map of `key.path: value` overrides applied like --set before the command line's.
enum class ConfigVariant { Full, Smoke };

//! A --set of a swept key replaces its axis (noted in `notes`); one overlapping a swept key
//! (a parent or child path of it) is refused. The `smoke:` block never reaches the runs.
//! \throw InvalidConfig naming the file (and line, for YAML syntax errors) or the key; for
//! the smoke variant of a file without a `smoke:` block.
YAML::Node load_experiment_config(const std::string& path, const std::vector<std::string>& sets,
                                  std::vector<std::string>* notes = nullptr, ConfigVariant variant = ConfigVariant::Full);

//! Sets a dotted key path, creating maps on the way. Under `sweep` (and `sweep.zip`) the rest
//! of the path is one key, since swept keys are themselves dotted paths.
void set_by_path(YAML::Node root, const std::string& dotted, const YAML::Node& value);
YAML::Node get_by_path(const YAML::Node& root, const std::string& dotted);  // undefined if absent

//! Maps merged recursively; anything else in `over` replaces `base`.
YAML::Node deep_merge(const YAML::Node& base, const YAML::Node& over);
YAML::Node deep_copy(const YAML::Node& n);

}  // namespace fairshape
