#include "fairshape/io/json_io.h"

#include "fairshape/core/atomic_file.h"
#include "fairshape/core/error.h"
#include "fairshape/io/text_scanner.h"

namespace fairshape {

void write_json(const nlohmann::json& j, const std::string& path) {
  write_atomically(path, [&](std::ostream& os) { os << j.dump(2) << '\n'; });
}

nlohmann::json read_json(const std::string& path) {
  try {
    return nlohmann::json::parse(io::internal::read_whole_file(path));
  } catch (const nlohmann::json::parse_error& e) {
    throw ParseError(path, 0, e.what());
  }
}

}  // namespace fairshape
