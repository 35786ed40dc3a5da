#include "fairshape/core/error.h"

namespace fairshape {

static std::string located(const std::string& file, long line, const std::string& problem) {
  std::string msg = file;
  if (line > 0) msg.append(":").append(std::to_string(line));
  msg.append(": ").append(problem);
  return msg;
}

ParseError::ParseError(const std::string& file, long line, const std::string& problem)
    : IOError(located(file, line, problem)), file_(file), line_(line) {}

}  // namespace fairshape

namespace fairshape::internal {

void assertion_failed(const char* cond, const char* file, int line, const std::string& msg) {
  throw std::logic_error(std::string(file) + ":" + std::to_string(line) +
                         ": internal error: assertion '" + cond + "' failed: " + msg);
}

}  // namespace fairshape::internal
