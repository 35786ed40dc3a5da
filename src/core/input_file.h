// Reading an input file whole, the one way every reader does it (meshes, curves, matrices,
// VTK headers, configs): regular files only — a FIFO would block the read and a device
// (/dev/zero, /dev/urandom) never ends — and no larger than the caller's limit.
#pragma once

#include <cstdint>
#include <string>

namespace fairshape {

//! The file's bytes. \throw IOError naming the path for a missing or unreadable file, a
//! directory, a device, a FIFO or a socket, or a file above `max_bytes`.
std::string read_regular_file(const std::string& path, std::uintmax_t max_bytes);

}  // namespace fairshape
