#include "fairshape/experiment/yaml_structure.h"

#include <map>
#include <sstream>
#include <vector>

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/mark.h>
#include <yaml-cpp/parser.h>

#include "fairshape/core/error.h"

namespace fairshape {
namespace {

class KeyChecker final : public YAML::EventHandler {
 public:
  explicit KeyChecker(std::string file) : file_(std::move(file)) {}
  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& m, YAML::anchor_t) override { on_value(m, "~"); }
  void OnAlias(const YAML::Mark& m, YAML::anchor_t) override { on_value(m, "*"); }
  void OnScalar(const YAML::Mark& m, const std::string&, YAML::anchor_t, const std::string& v) override { on_value(m, v); }
  void OnSequenceStart(const YAML::Mark& m, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    on_collection(m, false);
  }
  void OnSequenceEnd() override { frames_.pop_back(); }
  void OnMapStart(const YAML::Mark& m, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    on_collection(m, true);
  }
  void OnMapEnd() override { frames_.pop_back(); }

 private:
  struct Frame {
    bool is_map = false;
    bool expects_key = true;
    std::map<std::string, int> key_lines;
  };
  // A scalar in a map alternates between key and value.
  void on_value(const YAML::Mark& m, const std::string& v) {
    if (frames_.empty() || !frames_.back().is_map) return;
    Frame& f = frames_.back();
    if (f.expects_key) {
      const auto [it, fresh] = f.key_lines.emplace(v, m.line + 1);
      if (!fresh)
        throw InvalidConfig(file_ + ":" + std::to_string(m.line + 1) + ": key '" + v + "' repeats the key of line " +
                            std::to_string(it->second) + " (the later one would silently win)");
    }
    f.expects_key = !f.expects_key;
  }
  void on_collection(const YAML::Mark& m, bool is_map) {
    if (!frames_.empty() && frames_.back().is_map) {
      if (frames_.back().expects_key)
        throw InvalidConfig(file_ + ":" + std::to_string(m.line + 1) + ": a map key must be a plain value, not a list or a map");
      frames_.back().expects_key = true;
    }
    frames_.push_back({is_map, true, {}});
  }
  std::string file_;
  std::vector<Frame> frames_;
};

}  // namespace

void check_yaml_structure(const std::string& text, const std::string& file) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  KeyChecker checker(file);
  try {
    // The first document only, as YAML::Load reads it (on some malformed text yaml-cpp's
    // parser reports documents forever: a loop over them hung — found by fuzz_config).
    parser.HandleNextDocument(checker);
  } catch (const YAML::ParserException& e) {
    throw InvalidConfig(file + ":" + std::to_string(e.mark.line + 1) + ": YAML syntax error: " + e.msg);
  }
}

}  // namespace fairshape
