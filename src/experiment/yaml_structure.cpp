#include "fairshape/experiment/yaml_structure.h"

#include <cstdio>
#include <map>
#include <sstream>
#include <string_view>
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

// Where the document after the first begins (yaml-cpp reports each document's start).
class SecondDocument final : public YAML::EventHandler {
 public:
  void OnDocumentStart(const YAML::Mark& m) override { line = m.line + 1; }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t, const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
  int line = 0;
};

}  // namespace

void check_utf8(std::string_view text, const std::string& file) {
  // yaml-cpp decodes UTF-16 and UTF-32 itself (told by a byte-order mark or zero bytes at the
  // start): those are left to it.
  if (text.size() >= 2 && (text.substr(0, 2) == "\xFE\xFF" || text.substr(0, 2) == "\xFF\xFE")) return;
  if (text.substr(0, 4).find('\0') != std::string_view::npos) return;
  long line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < text.size();) {
    const auto b = static_cast<unsigned char>(text[i]);
    if (b == '\n') {
      ++line;
      line_start = i + 1;
    }
    if (b < 0x80) {
      ++i;
      continue;
    }
    // The length a lead byte announces, and the smallest code point of that length (smaller
    // ones are overlong forms).
    const std::size_t n = b >= 0xC2 && b <= 0xDF ? 2 : b >= 0xE0 && b <= 0xEF ? 3 : b >= 0xF0 && b <= 0xF4 ? 4 : 0;
    char32_t cp = n == 2 ? b & 0x1F : n == 3 ? b & 0x0F : b & 0x07;
    bool ok = n > 0 && i + n <= text.size();
    for (std::size_t k = 1; ok && k < n; ++k) {
      const auto c = static_cast<unsigned char>(text[i + k]);
      ok = (c & 0xC0) == 0x80;
      cp = (cp << 6) | (c & 0x3F);
    }
    ok = ok && !(n == 3 && cp < 0x800) && !(n == 4 && (cp < 0x10000 || cp > 0x10FFFF)) && !(cp >= 0xD800 && cp <= 0xDFFF);
    if (!ok) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", b);
      throw InvalidConfig(file + ":" + std::to_string(line) + ": byte " + hex + " at column " +
                          std::to_string(i - line_start + 1) +
                          " is not UTF-8 (a Latin-1 or other 8-bit character?): save the file as UTF-8");
    }
    i += n;
  }
}

void check_yaml_structure(const std::string& text, const std::string& file) {
  check_utf8(text, file);
  std::istringstream in(text);
  YAML::Parser parser(in);
  KeyChecker checker(file);
  try {
    // The first document, as YAML::Load reads it; then one more call only (on some malformed
    // text yaml-cpp's parser reports documents forever: a loop over them hung — found by
    // fuzz_config): a second document would be silently ignored.
    parser.HandleNextDocument(checker);
    SecondDocument second;
    if (parser.HandleNextDocument(second))
      throw InvalidConfig(file + ":" + std::to_string(second.line) +
                          ": a second YAML document starts here; a config is one document (its keys after this "
                          "'---' would be ignored): merge them into the first, or put them in a file of their own");
  } catch (const YAML::ParserException& e) {
    throw InvalidConfig(file + ":" + std::to_string(e.mark.line + 1) + ": YAML syntax error: " + e.msg);
  }
}

}  // namespace fairshape
