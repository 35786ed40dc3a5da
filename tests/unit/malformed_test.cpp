// Every file of tests/data/malformed must be rejected with a fairshape error that names the
// file, and nothing else: no crash, no other exception, no giant allocation (run under ASan
// by `make asan-test`).
#include <catch2/catch.hpp>

#include <filesystem>

#include "fairshape/io/mesh_io.h"
#include "test_support.h"

using namespace fairshape;
namespace fs = std::filesystem;

TEST_CASE("every malformed mesh file is rejected with a clear error", "[io][malformed]") {
  int files = 0;
  for (const auto& entry : fs::directory_iterator(test::source_path("tests/data/malformed"))) {
    const std::string path = entry.path().string();
    if (entry.path().extension() == ".py" || entry.path().filename() == "README.md") continue;
    ++files;
    INFO(path);
    try {
      (void)read_mesh(path);
      FAIL("accepted a malformed file");
    } catch (const Error& e) {
      const std::string msg = e.what();
      INFO(msg);
      CHECK(msg.find(entry.path().filename().string()) != std::string::npos);
      CHECK(msg.size() > path.size() + 10);  // says what is wrong, not only where
    }
  }
  CHECK(files >= 30);
}

TEST_CASE("parse errors carry the line number", "[io][malformed]") {
  try {
    (void)parse_off("OFF\n3 1 0\n0 0 0\n1 0 zz\n0 1 0\n3 0 1 2\n", "mem.off");
    FAIL("accepted");
  } catch (const ParseError& e) {
    CHECK(e.line() == 4);
    CHECK_THAT(e.what(), Catch::Matchers::Contains("mem.off:4:"));
  }
}

TEST_CASE("random truncations of valid files never crash", "[io][malformed]") {
  const std::string cow = "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n";
  int accepted = 0, rejected = 0;  // any other exception fails the test
  for (std::size_t n = 0; n <= cow.size(); ++n) {
    try {
      const MeshFile f = parse_off(cow.substr(0, n), "cut.off");
      (void)SurfaceMesh::from_polygons(f.vertices, f.faces);
      ++accepted;
    } catch (const Error&) {
      ++rejected;
    }
  }
  CHECK(accepted >= 1);  // the whole file (and the one missing its final newline)
  CHECK(rejected >= static_cast<int>(cow.size()) - 2);
}
