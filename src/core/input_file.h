// Reading an input file whole, the one way every reader does it (meshes, curves, matrices,
// VTK headers, configs): regular files only — a FIFO would block the read and a device
// (/dev/zero, /dev/urandom) never ends — and no larger than the caller's limit.
#pragma once

#include <cstdint>
#include <string>

#include "fairshape/core/error.h"

namespace fairshape {

//! An input file that does not exist: an IOError a caller can tell apart (Python raises it as a
//! FileNotFoundError).
class MissingFile : public IOError {
  using IOError::IOError;
};

//! The file's bytes. \throw MissingFile naming the path when nothing is there; IOError naming it for an unreadable file, a
//! directory, a device, a FIFO or a socket, or a file above `max_bytes`.
std::string read_regular_file(const std::string& path, std::uintmax_t max_bytes);

}  // namespace fairshape
