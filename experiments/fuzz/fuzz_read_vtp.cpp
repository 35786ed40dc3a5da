// libFuzzer target for the VTK XML polydata reader: any bytes, written to a file (VTK reads
// files), must either give a valid mesh or raise a fairshape::Error.
//   build-sanitize/bin/fuzz_read_vtp -max_total_time=30 tests/fuzz/vtp
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

#include "fairshape/core/error.h"
#include "fairshape/io/vtk_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/fairshape_fuzz_" + std::to_string(::getpid()) + ".vtp";
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    (void)fairshape::read_vtp(path);
  } catch (const fairshape::Error&) {
  }
  return 0;
}
