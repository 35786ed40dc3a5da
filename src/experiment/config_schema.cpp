#include "fairshape/experiment/config_schema.h"

#include <set>

#include <nlohmann/json.hpp>

#include "fairshape/experiment/components.h"
#include "fairshape/experiment/run_kind.h"

namespace fairshape {
namespace {

// Keys the config loader and the sweep read before a run kind sees the config (config_loader.h).
std::vector<OptionDoc> loader_keys() {
  return {{"defaults", "[]", "configs this one extends: a list of paths, later ones and this file override earlier ones"},
          {"smoke", "{}", "overrides (dotted keys) applied by `fairshape run --smoke`: the CI-sized variant"},
          {"sweep", "{}", "swept keys: {dotted.key: [values], zip: {key: [values], ...}}; the product of the lists"}};
}

// A documented default as JSON: numbers and booleans as such, "[]"/"{}" as empty containers.
nlohmann::json default_value(const std::string& text) {
  if (text == "[]") return nlohmann::json::array();
  if (text == "{}") return nlohmann::json::object();
  if (text == "true" || text == "false") return text == "true";
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size()) return v;
  } catch (const std::exception&) {
  }
  return text;
}

// The names a component `type` may take, by the key that selects it (a surface edit's
// registries; the other kinds list theirs in their docs).
std::vector<std::string> type_names(const std::string& kind, const std::string& path) {
  if (kind != "surface_edit") return {};
  const Components& c = components();
  if (path == "energy[].type") return c.energies.names();
  if (path == "constraints[].type") return c.constraints.names();
  if (path == "solver.type") return c.solvers.names();
  return {};
}

// Blocks whose keys depend on a component chosen by `type` (its options) or that name keys
// themselves (sweep): other keys are allowed there.
bool open_block(const std::string& path) {
  return path == "sweep" || path == "smoke" || path.rfind("solver", 0) == 0 || path.rfind("energy", 0) == 0 ||
         path.rfind("constraints", 0) == 0 || path.rfind("optimization", 0) == 0;
}

nlohmann::json& node_at(nlohmann::json& root, const std::string& path, std::string& walked) {
  nlohmann::json* node = &root;
  std::size_t start = 0;
  walked.clear();
  while (true) {
    const std::size_t dot = path.find('.', start);
    std::string part = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    const bool item = part.size() > 2 && part.compare(part.size() - 2, 2, "[]") == 0;
    if (item) part.resize(part.size() - 2);
    walked += (walked.empty() ? "" : ".") + part + (item ? "[]" : "");
    nlohmann::json& schema = (*node)["properties"][part];
    if (dot == std::string::npos && !item) return schema;
    if (item) {
      schema["type"] = "array";
      node = &schema["items"];
    } else {
      node = &schema;
    }
    node->emplace("type", "object");
    if (!open_block(walked)) node->emplace("additionalProperties", false);
    if (dot == std::string::npos) return *node;
    start = dot + 1;
  }
}

}  // namespace

std::vector<KindKeys> experiment_keys() {
  std::vector<KindKeys> out;
  for (const auto& kind : make_run_kinds()) {
    KindKeys k{kind->name(), kind->marker(), {}};
    std::set<std::string> seen;
    for (OptionDoc& d : kind->keys())
      if (seen.insert(d.key).second) k.keys.push_back(std::move(d));
    for (OptionDoc& d : loader_keys()) k.keys.push_back(std::move(d));
    out.push_back(std::move(k));
  }
  return out;
}

std::string experiment_schema(const std::vector<KindKeys>& kinds) {
  // One schema per kind, any of which a config may match: the kinds give some keys different
  // shapes (`energy` is a list of terms in a surface edit, a map of weights in a sheet run).
  nlohmann::json any_of = nlohmann::json::array();
  for (const KindKeys& k : kinds) {
    nlohmann::json schema = {{"title", k.kind + " run"},
                             {"description", "a config with " + k.marker},
                             {"type", "object"},
                             {"additionalProperties", false}};
    for (const OptionDoc& d : k.keys) {
      std::string walked;
      nlohmann::json& leaf = node_at(schema, d.key, walked);
      if (leaf.contains("description")) continue;  // read twice: the first read's words
      leaf["description"] = d.doc;
      if (d.default_value != "(required)" && !leaf.contains("type")) leaf["default"] = default_value(d.default_value);
      const std::vector<std::string> names = type_names(k.kind, walked);
      if (!names.empty()) leaf["enum"] = names;
    }
    any_of.push_back(std::move(schema));
  }
  const nlohmann::json schema = {{"$schema", "http://json-schema.org/draft-07/schema#"},
                                 {"title", "fairshape experiment config"},
                                 {"description", "The keys every fairshape run kind reads (`fairshape list --keys`)."},
                                 {"anyOf", any_of}};
  return schema.dump(2) + "\n";
}

}  // namespace fairshape
