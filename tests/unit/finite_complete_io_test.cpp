// Readers that take the whole of a file (a curve in several pieces), writers that never write a
// non-finite number, configs that are one UTF-8 document.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <limits>

#include "fairshape/core/error.h"
#include "fairshape/experiment/yaml_structure.h"
#include "fairshape/io/matrix_market.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/io/vtk_io.h"
#include "test_support.h"

using namespace fairshape;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

// Points (i, i², 0), i = 1..n, then the given `l` statements.
fs::path curve_file(const fs::path& dir, const std::string& name, int n, const std::vector<std::string>& lines) {
  const fs::path p = dir / (name + ".obj");
  std::ofstream out(p);
  for (int i = 1; i <= n; ++i) out << "v " << i << ' ' << i * i << " 0\n";
  for (const auto& l : lines) out << l << '\n';
  return p;
}

std::string ids(int from, int to) {  // "l from … to", either direction
  std::string s = "l";
  for (int i = from; from <= to ? i <= to : i >= to; i += from <= to ? 1 : -1) s += ' ' + std::to_string(i);
  return s;
}

bool nothing_left(const fs::path& dir, const std::string& stem) {
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind(stem, 0) == 0) return false;
  return true;
}

}  // namespace

TEST_CASE("a curve in several `l` statements is read whole, or refused naming the lines", "[io]") {
  const auto dir = test::scratch_dir("io_polyline_pieces");
  SECTION("pieces that continue each other are one curve") {
    for (const auto& lines : std::vector<std::vector<std::string>>{{ids(1, 65), ids(65, 129)},
                                                                   {ids(1, 65), ids(129, 65)},
                                                                   {ids(65, 1), ids(65, 129)},
                                                                   {ids(1, 40), ids(40, 90), ids(129, 90)}}) {
      const Polyline c = read_polyline(curve_file(dir, "pieces", 129, lines).string());
      REQUIRE(c.n_points() == 129);
      CHECK_FALSE(c.closed);
      for (int i = 0; i < 129; ++i) CHECK(c.points(i, 0) == i + 1);
    }
  }
  SECTION("a closed curve in two pieces") {
    const Polyline c = read_polyline(curve_file(dir, "loop", 8, {ids(1, 5), ids(5, 8) + " 1"}).string());
    CHECK(c.closed);
    CHECK(c.n_points() == 8);
  }
  SECTION("pieces that meet at duplicated vertices") {
    std::ofstream(dir / "dup.obj") << "v 0 0 0\nv 1 0 0\nv 1 0 0\nv 2 0 0\nl 1 2\nl 3 4\n";
    const Polyline c = read_polyline((dir / "dup.obj").string());
    CHECK(c.n_points() == 3);
  }
  SECTION("pieces that do not meet are refused, with their lines") {
    const fs::path p = curve_file(dir, "apart", 129, {ids(1, 64), ids(66, 129)});
    CHECK_THROWS_AS(read_polyline(p.string()), ParseError);
    CHECK_THROWS_WITH(read_polyline(p.string()),
                      Contains("apart.obj:131: this polyline (vertices 66 to 129) does not continue the curve of line(s) 130, "
                               "which ends at vertex 64"));
  }
}

TEST_CASE("writers refuse non-finite numbers, naming where, and leave nothing behind", "[io]") {
  const auto dir = test::scratch_dir("io_non_finite");
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  SurfaceMesh m = test::grid(2);
  m.positions()(3, 1) = inf;
  for (const char* ext : {".obj", ".off", ".ply", ".vtp"}) {
    const std::string path = (dir / (std::string("mesh") + ext)).string();
    CHECK_THROWS_WITH(std::string(ext) == ".vtp" ? write_vtp(m, path) : write_mesh(m, path),
                      Contains("not written: vertex 3 has a non-finite value (") && Contains(" inf "));
  }
  CHECK_THROWS_AS(write_vtm({{"level0", &m}}, (dir / "mesh.vtm").string()), SolverError);
  Polyline c{MatrixX3::Zero(3, 3), false};
  c.points(2, 2) = nan;
  CHECK_THROWS_WITH(write_polyline(c, (dir / "mesh_curve.obj").string()), Contains("vertex 2 has a non-finite value"));
  SurfaceMesh data = test::grid(2);
  data.vertex_data["displacement"] = Eigen::MatrixXd::Zero(data.n_vertices(), 3);
  data.vertex_data["displacement"](1, 0) = nan;
  CHECK_THROWS_WITH(write_vtp(data, (dir / "mesh_data.vtp").string()), Contains("data array 'displacement' row 1"));
  SparseMatrix A(2, 2);
  A.insert(1, 0) = -inf;
  CHECK_THROWS_WITH(write_matrix_market(A, (dir / "mesh_A.mtx").string(), false), Contains("entry (1, 0) is -inf"));
  Eigen::MatrixXd M = Eigen::MatrixXd::Ones(2, 2);
  M(0, 1) = nan;
  CHECK_THROWS_WITH(write_matrix_market(M, (dir / "mesh_M.mtx").string()), Contains("row 0 has a non-finite value"));
  CHECK(nothing_left(dir, "mesh"));
}

TEST_CASE("a config is one UTF-8 YAML document", "[config]") {
  CHECK_NOTHROW(check_yaml_structure("name: café\n", "ok.yaml"));
  CHECK_NOTHROW(check_yaml_structure("---\nname: café 😀\n...\n", "ok.yaml"));
  CHECK_THROWS_WITH(check_yaml_structure("name: a\n---\nname: b\n", "two.yaml"), Contains("two.yaml:2: a second YAML document"));
  CHECK_THROWS_WITH(check_yaml_structure("a: 1\nname: caf\xe9\n", "latin1.yaml"), Contains("latin1.yaml:2: byte 0xE9 at column 10"));
  CHECK_THROWS_WITH(check_utf8("a: \xc0\xaf", "overlong"), Contains("byte 0xC0"));
  CHECK_THROWS_WITH(check_utf8("a: \xed\xa0\x80", "surrogate"), Contains("byte 0xED"));
  CHECK_THROWS_WITH(check_utf8("a: \xe2\x82", "cut"), Contains("byte 0xE2"));
  CHECK_NOTHROW(check_utf8("a: \xf0\x9f\x98\x80", "emoji"));
}
