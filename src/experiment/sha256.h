// SHA-256 digests (OpenSSL's EVP interface) for provenance: the input files a run read and
// the identity of run configurations.
#pragma once

#include <string>
#include <string_view>

namespace fairshape {

//! 64 lowercase hex digits.
std::string sha256_hex(std::string_view data);
//! The digest of a file's bytes, read in blocks. \throw IOError when it cannot be read.
std::string sha256_file_hex(const std::string& path);

}  // namespace fairshape
