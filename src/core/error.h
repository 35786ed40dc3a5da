// Typed exceptions for everything driven by input: files, configs, meshes, solvers.
// Messages start with the function or file that raised them, so a user can act on them.
#pragma once

#include <stdexcept>
#include <string>

namespace fairshape {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class InvalidInput : public Error { using Error::Error; };
class InvalidConfig : public Error { using Error::Error; };
class TopologyError : public Error { using Error::Error; };
class IOError : public Error { using Error::Error; };
class SolverError : public Error { using Error::Error; };
//! Writing an output failed (disk full, a file-size limit, permissions): the run's results are
//! incomplete, so it is not a finished run (termination output_failed; --resume runs it again).
class OutputError : public IOError { using IOError::IOError; };

// A parse error at a known place in a file: "cow.off:12: expected 3 coordinates".
class ParseError : public IOError {
 public:
  ParseError(const std::string& file, long line, const std::string& problem);
  const std::string& file() const { return file_; }
  long line() const { return line_; }

 private:
  std::string file_;
  long line_;
};

namespace internal {
[[noreturn]] void assertion_failed(const char* cond, const char* file, int line,
                                   const std::string& msg);
}  // namespace internal

}  // namespace fairshape

// Programmer errors (never config-driven): throws with file and line.
#define FAIRSHAPE_ASSERT(cond, msg)                                                  \
  do {                                                                               \
    if (!(cond)) ::fairshape::internal::assertion_failed(#cond, __FILE__, __LINE__, (msg)); \
  } while (0)
