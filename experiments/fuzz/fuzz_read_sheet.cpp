// libFuzzer target for the sheet-file reader (bspline/sheet_file.h): any text must either read
// as a sheet — which then evaluates and saves again — or raise a fairshape::Error; never a
// crash, a hang or a huge allocation from a header's counts.
//   build-sanitize/bin/fuzz_read_sheet -max_total_time=30 tests/fuzz/sheet
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string_view>

#include "fairshape/bspline/sheet_file.h"
#include "fairshape/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const fairshape::bspline::VariationalSheet sheet = fairshape::bspline::parse_sheet(text, "fuzz.sheet");
    const auto& shape = sheet.surface().shape();
    (void)sheet.surface().position(sheet.coefficients(), 0.5 * shape.spans_u, 0.5 * shape.spans_v);
    std::ostringstream out;
    fairshape::bspline::write_sheet(out, sheet);
  } catch (const fairshape::Error&) {
  }
  return 0;
}
