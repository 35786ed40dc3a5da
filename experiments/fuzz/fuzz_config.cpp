// libFuzzer target for the config layer's parsing: any text must either load — structure
// checked (repeated and non-scalar keys), YAML parsed, every key read through Config — or
// raise a fairshape::Error; never a YAML exception, a crash or a hang.
//   build-sanitize/bin/fuzz_config -max_total_time=30 tests/fuzz/config
#include <cstddef>
#include <cstdint>
#include <string>

#include "fairshape/core/config.h"
#include "fairshape/experiment/yaml_structure.h"

namespace {
// Every key of every map, read as the config layer reads them (strings, numbers, children).
void walk(fairshape::Config c, int depth) {
  if (depth > 64) return;
  for (const auto& kv : c.node()) {
    if (!kv.first.IsScalar()) throw fairshape::InvalidConfig("non-scalar key");
    const std::string key = kv.first.Scalar();
    if (kv.second.IsMap()) walk(c.child(key, ""), depth + 1);
    else if (kv.second.IsSequence()) (void)c.child_list(key, "");
    else if (kv.second.IsScalar()) (void)c.get<double>(key, 0.0, "");
  }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    fairshape::check_yaml_structure(text, "fuzz.yaml");
    const YAML::Node root = YAML::Load(text);
    if (root.IsMap()) walk(fairshape::Config(root, ""), 0);
  } catch (const fairshape::Error&) {
  } catch (const YAML::Exception&) {
    // Past check_yaml_structure the text parses; YAML::Load can still refuse what the event
    // parser allowed (e.g. tags): the loader turns those into InvalidConfig too.
  }
  return 0;
}
