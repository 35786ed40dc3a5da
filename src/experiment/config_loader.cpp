#include "fairshape/experiment/config_loader.h"

#include <filesystem>
#include <map>
#include <vector>

#include "fairshape/core/config.h"
#include "fairshape/core/error.h"
#include "fairshape/core/input_file.h"
#include "fairshape/experiment/yaml_structure.h"

namespace fairshape {
namespace fs = std::filesystem;
namespace {

// The largest config file read: a config is a page of YAML, not data.
constexpr std::uintmax_t kMaxConfigBytes = 16u << 20;

YAML::Node parse_file(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InvalidConfig(path.string() + ": config file not found");
  std::string text;
  try {
    text = read_regular_file(path.string(), kMaxConfigBytes);
  } catch (const IOError& e) {
    throw InvalidConfig(e.what());
  }
  check_yaml_structure(text, path.string());
  try {
    return YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InvalidConfig(path.string() + ":" + std::to_string(e.mark.line + 1) + ": YAML syntax error: " + e.msg);
  }
}

// One load of a config and everything it includes: each file is read and merged once (a
// diamond of includes is linear, not exponential), and a file that includes itself, directly
// or not, is refused with the chain.
// deep_merge without copying `over`: its subtrees move into `base`. For a file just parsed,
// which nothing else holds, so a large sweep is not copied once more.
void merge_sharing(YAML::Node base, const YAML::Node& over) {
  for (const auto& kv : over) {
    const std::string key = kv.first.as<std::string>();
    if (kv.second.IsMap() && base[key] && base[key].IsMap()) merge_sharing(base[key], kv.second);
    else base[key] = kv.second;
  }
}

class DefaultsLoader {
 public:
  YAML::Node load(const fs::path& path) {
    std::error_code ec;
    const fs::path key = fs::weakly_canonical(path, ec);
    if (const auto it = loaded_.find(key); it != loaded_.end()) return YAML::Clone(it->second);
    for (const auto& open : chain_)
      if (open == key) throw InvalidConfig(path.string() + ": `defaults` include themselves (" + chain_text() + " -> " + path.string() + ")");
    if (chain_.size() > 16) throw InvalidConfig(path.string() + ": `defaults` nest more than 16 deep");
    chain_.push_back(key);
    YAML::Node node = parse_file(path);
    if (node.IsNull()) node = YAML::Node(YAML::NodeType::Map);
    if (!node.IsMap()) throw InvalidConfig(path.string() + ": the top level must be a map of keys");
    YAML::Node merged(YAML::NodeType::Map);
    if (const YAML::Node defaults = node["defaults"]) {
      if (!defaults.IsSequence()) throw InvalidConfig(path.string() + ": `defaults` must be a list of YAML files");
      for (const auto& d : defaults) {
        if (!d.IsScalar())
          throw InvalidConfig(path.string() + ":" + std::to_string(d.Mark().line + 1) + ": a `defaults` entry must be a file name");
        merged = deep_merge(merged, load(path.parent_path() / d.Scalar()));
      }
      node.remove("defaults");
    }
    chain_.pop_back();
    merge_sharing(merged, node);
    YAML::Node out = merged;
    // Only included files can be asked for again; the experiment file itself (with its sweep,
    // possibly large) is not kept twice.
    if (!chain_.empty()) loaded_.emplace(key, YAML::Clone(out));
    return out;
  }

 private:
  std::string chain_text() const {
    std::string out;
    for (const auto& p : chain_) out.append(out.empty() ? "" : " -> ").append(p.string());
    return out;
  }
  std::map<fs::path, YAML::Node> loaded_;
  std::vector<fs::path> chain_;
};

}  // namespace

YAML::Node deep_copy(const YAML::Node& n) { return YAML::Clone(n); }

YAML::Node deep_merge(const YAML::Node& base, const YAML::Node& over) {
  if (!base.IsMap() || !over.IsMap()) return YAML::Clone(over);
  YAML::Node out = YAML::Clone(base);
  for (const auto& kv : over) {
    const std::string key = kv.first.as<std::string>();
    out[key] = out[key] && out[key].IsMap() ? deep_merge(out[key], kv.second) : YAML::Clone(kv.second);
  }
  return out;
}

static std::vector<std::string> split_path(const std::string& dotted) {
  std::vector<std::string> parts;
  std::string cur;
  for (char c : dotted) {
    if (c == '.') { parts.push_back(cur); cur.clear(); }
    else cur += c;
  }
  parts.push_back(cur);
  // Under `sweep` (and `sweep.zip`) the remainder is one dotted key.
  if (parts.size() > 1 && parts[0] == "sweep") {
    const std::size_t head = parts.size() > 2 && parts[1] == "zip" ? 2 : 1;
    std::string rest;
    for (std::size_t i = head; i < parts.size(); ++i) rest += (i > head ? "." : "") + parts[i];
    parts.resize(head);
    parts.push_back(rest);
  }
  return parts;
}

namespace {
// A path part naming an existing list element ("edits.0.level"): its index, else −1.
int list_index(const YAML::Node& n, const std::string& part) {
  if (!n.IsSequence() || part.empty() || part.find_first_not_of("0123456789") != std::string::npos) return -1;
  const std::size_t i = std::stoul(part);
  return i < n.size() ? static_cast<int>(i) : -1;
}
}  // namespace

void set_by_path(YAML::Node root, const std::string& dotted, const YAML::Node& value) {
  const auto parts = split_path(dotted);
  for (const auto& p : parts)
    if (p.empty()) throw InvalidConfig("--set " + dotted + ": empty key in the path");
  YAML::Node cur = root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    if (const int k = list_index(cur, parts[i]); k >= 0) {
      cur.reset(cur[k]);
      continue;
    }
    YAML::Node next = cur[parts[i]];
    if (!next || next.IsNull()) {
      cur[parts[i]] = YAML::Node(YAML::NodeType::Map);
      next = cur[parts[i]];
    } else if (!next.IsMap() && list_index(next, parts[i + 1]) < 0) {
      throw InvalidConfig("--set " + dotted + ": '" + parts[i] + "' holds a value, not a map of keys");
    }
    cur.reset(next);
  }
  if (const int k = list_index(cur, parts.back()); k >= 0) cur[k] = value;
  else cur[parts.back()] = value;
}

YAML::Node get_by_path(const YAML::Node& root, const std::string& dotted) {
  YAML::Node cur = YAML::Clone(root);
  for (const auto& p : split_path(dotted)) {
    if (const int k = list_index(cur, p); k >= 0) {
      cur.reset(cur[k]);
      continue;
    }
    if (!cur.IsMap() || !cur[p]) return YAML::Node(YAML::NodeType::Undefined);
    cur.reset(cur[p]);
  }
  return cur;
}

namespace {

bool is_under(const std::string& key, const std::string& prefix) {
  return key.size() > prefix.size() && key.compare(0, prefix.size(), prefix) == 0 && key[prefix.size()] == '.';
}

// A --set of a key the sweep varies replaces that axis (the key leaves its list or its zip);
// a --set above or below a swept key would be half-overwritten by it, so it is refused.
void take_key_out_of_sweep(YAML::Node root, const std::string& key, std::vector<std::string>* notes) {
  if (key == "sweep" || is_under(key, "sweep")) return;  // the sweep itself is being set
  YAML::Node sweep = root["sweep"];
  if (!sweep || !sweep.IsMap()) return;
  auto visit = [&](YAML::Node axes, const std::string& where) {
    std::vector<std::string> keys;
    for (const auto& kv : axes)
      if (kv.first.IsScalar() && kv.first.as<std::string>() != "zip") keys.push_back(kv.first.as<std::string>());
    for (const auto& swept : keys) {
      if (swept == key) {
        axes.remove(swept);
        if (notes) notes->push_back("--set " + key + " replaces the sweep axis " + where + swept);
      } else if (is_under(swept, key) || is_under(key, swept)) {
        throw InvalidConfig("--set " + key + ": overlaps the swept key " + where + swept +
                            " (set the swept key itself, or the sweep with --set '" + where + swept + "=[...]')");
      }
    }
  };
  visit(sweep, "sweep.");
  if (YAML::Node zip = sweep["zip"]; zip && zip.IsMap()) {
    visit(zip, "sweep.zip.");
    if (zip.size() == 0) sweep.remove("zip");
  }
  if (sweep.size() == 0) root.remove("sweep");
}

}  // namespace

YAML::Node load_experiment_config(const std::string& path, const std::vector<std::string>& sets,
                                  std::vector<std::string>* notes, ConfigVariant variant) {
  YAML::Node root = DefaultsLoader().load(path);
  const YAML::Node smoke = root["smoke"];
  if (smoke && !smoke.IsMap())
    throw InvalidConfig(path + ": smoke: expected a map of key.path: value overrides (the CI-sized variant)");
  if (smoke) root.remove("smoke");
  if (variant == ConfigVariant::Smoke) {
    if (!smoke) throw InvalidConfig(path + ": --smoke: the file has no smoke: block of overrides");
    for (const auto& kv : smoke) {
      const std::string key = kv.first.as<std::string>();
      take_key_out_of_sweep(root, key, nullptr);
      set_by_path(root, key, deep_copy(kv.second));
    }
  }
  for (const auto& s : sets) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InvalidConfig("--set '" + s + "': expected key.path=value");
    check_utf8(s, "--set '" + s.substr(0, eq) + "'");  // before anything is written (config.resolved.yaml)
    YAML::Node value;
    try {
      value = YAML::Load(s.substr(eq + 1));
    } catch (const YAML::Exception& e) {
      throw InvalidConfig("--set '" + s + "': value is not valid YAML: " + e.msg);
    }
    take_key_out_of_sweep(root, s.substr(0, eq), notes);
    set_by_path(root, s.substr(0, eq), value);
  }
  return root;
}

}  // namespace fairshape
