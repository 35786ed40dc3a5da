// libFuzzer target for one mesh reader, chosen at compile time (FAIRSHAPE_FUZZ_FORMAT = 0 OBJ,
// 1 OFF, 2 PLY). Any input must either parse into a valid mesh or raise a fairshape::Error.
//   cmake --preset sanitize && cmake --build build-sanitize && build-sanitize/bin/fuzz_read_off -max_total_time=60
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fairshape/io/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    fairshape::MeshFile f;
    if constexpr (FAIRSHAPE_FUZZ_FORMAT == 0) f = fairshape::parse_obj(text, "fuzz.obj");
    if constexpr (FAIRSHAPE_FUZZ_FORMAT == 1) f = fairshape::parse_off(text, "fuzz.off");
    if constexpr (FAIRSHAPE_FUZZ_FORMAT == 2) f = fairshape::parse_ply(text, "fuzz.ply");
    (void)fairshape::SurfaceMesh::from_polygons(f.vertices, f.faces);
  } catch (const fairshape::Error&) {
  }
  return 0;
}
