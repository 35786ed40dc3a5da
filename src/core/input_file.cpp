#include "fairshape/core/input_file.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "fairshape/core/error.h"

namespace fairshape {

std::string read_regular_file(const std::string& path, std::uintmax_t max_bytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (status.type() == fs::file_type::not_found) throw MissingFile(path + ": cannot open for reading (no such file)");
  if (ec || !fs::exists(status)) throw IOError(path + ": cannot open for reading (missing file or no permission)");
  if (fs::is_directory(status)) throw IOError(path + ": is a directory, not a file");
  if (!fs::is_regular_file(status))
    throw IOError(path + ": not a regular file (a device, FIFO or socket); fairshape reads regular files only");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > max_bytes)
    throw IOError(path + ": " + std::to_string(size) + " bytes, above the input limit of " + std::to_string(max_bytes >> 20) +
                  " MiB");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IOError(path + ": cannot open for reading (missing file or no permission)");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw IOError(path + ": read error");
  return ss.str();
}

}  // namespace fairshape
