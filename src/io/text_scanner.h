// Line-by-line tokenizer over an in-memory file, for the mesh readers. Every failure
// raises a ParseError naming the file and the 1-based line.
#pragma once

#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "fairshape/core/error.h"

namespace fairshape::io::internal {

class TextScanner {
 public:
  TextScanner(std::string_view text, std::string file, long first_line = 1)
      : text_(text), file_(std::move(file)), line_(first_line - 1) {}

  // Advances to the next line that is not blank or a '#' comment; false at end of file.
  // The line's tokens are then available through tokens().
  bool next_line();
  const std::vector<std::string_view>& tokens() const { return tokens_; }
  long line() const { return line_; }
  std::size_t remaining_bytes() const { return text_.size() - pos_; }
  const std::string& file() const { return file_; }

  [[noreturn]] void fail(const std::string& problem) const { throw ParseError(file_, line_, problem); }
  double to_double(std::string_view tok, const char* what) const;
  long long to_integer(std::string_view tok, const char* what) const;
  // A count that must fit the bytes left (each item needs at least min_bytes_each bytes),
  // so an absurd header count is an error before anything is allocated.
  long long to_count(std::string_view tok, const char* what, std::size_t min_bytes_each) const;

 private:
  std::string_view text_;
  std::string file_;
  std::size_t pos_ = 0;
  long line_;
  std::vector<std::string_view> tokens_;
};

//! The largest input file read (meshes, curves, matrices): 2 GiB.
inline constexpr std::uintmax_t kMaxInputBytes = std::uintmax_t{2} << 30;
//! The file's bytes, a leading UTF-8 byte-order mark dropped. \throw IOError for a missing,
//! unreadable or oversized file, a directory, a device, a FIFO or a socket.
std::string read_whole_file(const std::string& path);

}  // namespace fairshape::io::internal
