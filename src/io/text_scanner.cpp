#include "fairshape/io/text_scanner.h"

#include <cmath>

#include "fairshape/core/input_file.h"

namespace fairshape::io::internal {

bool TextScanner::next_line() {
  while (pos_ < text_.size()) {
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    std::string_view line = text_.substr(pos_, end - pos_);
    pos_ = end + 1 > text_.size() ? text_.size() : end + 1;
    ++line_;
    if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    tokens_.clear();
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      std::size_t j = i;
      while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
      if (j > i) tokens_.push_back(line.substr(i, j - i));
      i = j;
    }
    if (!tokens_.empty()) return true;
  }
  tokens_.clear();
  return false;
}

double TextScanner::to_double(std::string_view tok, const char* what) const {
  double v = 0;
  const char* first = tok.data();
  if (!tok.empty() && tok[0] == '+') ++first;  // from_chars rejects a leading '+'
  auto [ptr, ec] = std::from_chars(first, tok.data() + tok.size(), v);
  if (ec != std::errc() || ptr != tok.data() + tok.size())
    fail(std::string("expected a number for ") + what + ", got '" + std::string(tok.substr(0, 40)) + "'");
  if (!std::isfinite(v)) fail(std::string(what) + " is not finite ('" + std::string(tok) + "')");
  return v;
}

long long TextScanner::to_integer(std::string_view tok, const char* what) const {
  long long v = 0;
  auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
  if (ec != std::errc() || ptr != tok.data() + tok.size())
    fail(std::string("expected an integer for ") + what + ", got '" + std::string(tok.substr(0, 40)) + "'");
  return v;
}

long long TextScanner::to_count(std::string_view tok, const char* what, std::size_t min_bytes_each) const {
  const long long n = to_integer(tok, what);
  if (n < 0) fail(std::string(what) + " is negative (" + std::to_string(n) + ")");
  if (static_cast<unsigned long long>(n) > remaining_bytes() / min_bytes_each + 1)
    fail(std::string(what) + " is " + std::to_string(n) + " but only " +
         std::to_string(remaining_bytes()) + " bytes follow (file truncated or count wrong)");
  return n;
}

std::string read_whole_file(const std::string& path) {
  std::string text = read_regular_file(path, kMaxInputBytes);
  // A UTF-8 byte-order mark (some editors write one) is not part of the first line.
  if (text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);
  return text;
}

}  // namespace fairshape::io::internal
