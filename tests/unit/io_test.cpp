#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "fairshape/core/error.h"
#include "fairshape/io/csv.h"
#include "fairshape/io/json_io.h"
#include "fairshape/io/matrix_market.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/io/vtk_io.h"
#include "test_support.h"

using namespace fairshape;
namespace fs = std::filesystem;

namespace {

// Positions perturbed off the decimal grid so a lossy writer would show.
SurfaceMesh irrational_cow() {
  SurfaceMesh m = read_mesh(test::data_path("cow.off"));
  m.positions() *= M_PI / 3.0;
  return m;
}

}  // namespace

TEST_CASE("mesh formats round-trip bit-exactly", "[io]") {
  const auto dir = test::scratch_dir("io_roundtrip");
  const SurfaceMesh m = irrational_cow();
  for (const std::string name : {"a.obj", "a.off", "a.ply", "b.ply"}) {
    INFO(name);
    const std::string path = (dir / name).string();
    write_mesh(m, path, {name == "b.ply"});
    const SurfaceMesh back = read_mesh(path);
    CHECK(back.positions() == m.positions());
    CHECK(back.polygons() == m.polygons());
  }
  const SurfaceMesh quads = read_mesh(test::data_path("double-torus-example.off"));  // mixed polygon sizes
  write_mesh(quads, (dir / "q.ply").string(), {true});
  CHECK(read_mesh((dir / "q.ply").string()).polygons() == quads.polygons());
}

TEST_CASE("OBJ reader: v/vt/vn forms, negative indices, polylines, skipped statements", "[io]") {
  const MeshFile f = parse_obj(
      "# test\nmtllib x.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0 1.0\nvt 0 0\nvn 0 0 1\n"
      "g part\ns off\nf 1/1/1 2/1/1 3/1/1\nf 2//1 4//1 3//1\nf -3 -1 -2\nl 1 2 4\nt crease 2/1/0 1 2 3\nt hole 1/0/0 0\n",
      "mem.obj");
  REQUIRE(f.vertices.rows() == 4);
  REQUIRE(f.faces.size() == 3);
  CHECK(f.faces[0] == std::vector<int>{0, 1, 2});
  CHECK(f.faces[1] == std::vector<int>{1, 3, 2});
  CHECK(f.faces[2] == std::vector<int>{1, 3, 2});
  REQUIRE(f.lines.size() == 1);
  CHECK(f.lines[0] == std::vector<int>{0, 1, 3});
  REQUIRE(f.sharpness.size() == 1);  // OpenSubdiv's crease tag is read (tests/unit/crease_test.cpp)
  CHECK((f.sharpness[0].a == 1 && f.sharpness[0].b == 2 && f.sharpness[0].sharpness == 3.0));
  REQUIRE(f.warnings.size() == 1);  // other tags are reported, not silently dropped
  CHECK_THAT(f.warnings[0], Catch::Matchers::Contains("'t hole'"));
}

TEST_CASE("PLY reader: big-endian binary and extra elements/properties", "[io]") {
  std::string bytes =
      "ply\nformat binary_big_endian 1.0\ncomment hi\nelement vertex 3\nproperty double x\nproperty double y\n"
      "property double z\nproperty uchar red\nelement face 1\nproperty list uchar int vertex_indices\n"
      "element edge 1\nproperty int a\nend_header\n";
  auto put_be = [&bytes](const void* p, std::size_t n) {
    const auto* c = static_cast<const char*>(p);
    for (std::size_t i = n; i-- > 0;) bytes.push_back(c[i]);
  };
  const double coords[9] = {0, 0, 0, 1.5, 0, 0, 0, 2.5, 0};
  for (int v = 0; v < 3; ++v) {
    for (int k = 0; k < 3; ++k) put_be(&coords[3 * v + k], 8);
    bytes.push_back('\x7f');
  }
  bytes.push_back('\x03');
  for (int id : {0, 1, 2}) put_be(&id, 4);
  const int edge = 42;
  put_be(&edge, 4);
  const MeshFile f = parse_ply(bytes, "mem.ply");
  REQUIRE(f.vertices.rows() == 3);
  CHECK(f.vertices(1, 0) == 1.5);
  CHECK(f.vertices(2, 1) == 2.5);
  REQUIRE(f.faces.size() == 1);
  CHECK(f.faces[0] == std::vector<int>{0, 1, 2});
}

TEST_CASE("polylines round-trip through OBJ, open and closed", "[io]") {
  const auto dir = test::scratch_dir("io_polyline");
  for (bool closed : {false, true}) {
    Polyline c;
    c.closed = closed;
    c.points = MatrixX3::Random(9, 3);
    write_polyline(c, (dir / "c.obj").string());
    const Polyline back = read_polyline((dir / "c.obj").string());
    CHECK(back.closed == closed);
    CHECK(back.points == c.points);
  }
}

TEST_CASE("VTK: vtp with point and cell data, vtm with several blocks, pvd series", "[io][vtk]") {
  const auto dir = test::scratch_dir("io_vtk");
  SurfaceMesh m = test::grid(3);
  m.vertex_data["displacement"] = Eigen::MatrixXd::Random(m.n_vertices(), 3);
  m.face_data["feature"] = Eigen::MatrixXd::Ones(m.n_faces(), 1);
  write_vtp(m, (dir / "m.vtp").string());
  const SurfaceMesh back = read_vtp((dir / "m.vtp").string());
  CHECK(back.positions() == m.positions());
  CHECK(back.polygons() == m.polygons());
  CHECK(back.vertex_data.at("displacement") == m.vertex_data.at("displacement"));
  CHECK(back.face_data.at("feature") == m.face_data.at("feature"));

  const SurfaceMesh fine = test::grid(6, true);
  write_vtm({{"level0", &m}, {"level1", &fine}}, (dir / "h.vtm").string());
  const auto blocks = read_vtm((dir / "h.vtm").string());
  REQUIRE(blocks.size() == 2);
  CHECK(blocks[1].positions() == fine.positions());
  CHECK(blocks[1].n_faces() == fine.n_faces());
  {  // VTK reads a .vtm's pieces itself: an absurd count in a piece is refused before it does.
    const fs::path piece = dir / "h" / "h_1.vtp";
    REQUIRE(fs::exists(piece));
    std::ifstream pin(piece, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(pin)), {});
    pin.close();
    const std::size_t at = text.find("NumberOfPoints=\"");
    REQUIRE(at != std::string::npos);
    text.insert(at + 16, "9999999999");
    std::ofstream(piece, std::ios::binary) << text;
    CHECK_THROWS_WITH(read_vtm((dir / "h.vtm").string()),
                      Catch::Matchers::Contains("h_1.vtp:") && Catch::Matchers::Contains("NumberOfPoints=\"9999999999"));
  }

  write_pvd({{0.0, "m.vtp"}, {1.0, "m.vtp"}}, (dir / "s.pvd").string());
  std::ifstream in(dir / "s.pvd");
  const std::string xml((std::istreambuf_iterator<char>(in)), {});
  CHECK_THAT(xml, Catch::Matchers::Contains("type=\"Collection\""));
  CHECK_THAT(xml, Catch::Matchers::Contains("file=\"m.vtp\""));

  // Nothing temporary is left behind.
  for (const auto& e : fs::directory_iterator(dir)) CHECK(e.path().string().find(".tmp.") == std::string::npos);
}

TEST_CASE("CSV follows RFC 4180 and round-trips awkward fields", "[io]") {
  const auto dir = test::scratch_dir("io_csv");
  CsvTable t;
  t.header = {"a", "b,c", "d"};
  t.rows = {{"plain", "with \"quotes\"", "multi\nline"}, {"", "x", "trailing,comma,"}};
  write_csv(t, (dir / "t.csv").string());
  const CsvTable back = read_csv((dir / "t.csv").string());
  CHECK(back.header == t.header);
  CHECK(back.rows == t.rows);
  CHECK(csv_escape("a\"b") == "\"a\"\"b\"");
  // A final record without a line break is legal (RFC 4180); a sweep's reader drops it as cut.
  CHECK(parse_csv("a,b\r\n1,2\r\n3,", "x", false).rows.size() == 2);
  CHECK(parse_csv("a,b\r\n1,2\r\n3,", "x", true).rows.size() == 1);
  CHECK_THROWS_AS(parse_csv("a,b\r\n1,\"open", "x", false), ParseError);
  CHECK_THROWS_AS(parse_csv("a,b\r\n1,2,3\r\n", "x", false), ParseError);
}

TEST_CASE("CsvAppender and truncate_partial_tail keep only whole records", "[io]") {
  const auto dir = test::scratch_dir("io_append");
  const std::string p = (dir / "r.csv").string();
  {
    CsvAppender a(p);
    a.append({"h1", "h2"});
    a.append({"1", "2"});
  }
  std::ofstream(p, std::ios::app) << "3,4-partial";
  truncate_partial_tail(p);
  const CsvTable t = read_csv(p);
  CHECK(t.rows.size() == 1);
  CHECK(t.rows[0] == std::vector<std::string>{"1", "2"});
}

TEST_CASE("Matrix Market and JSON round trips", "[io]") {
  const auto dir = test::scratch_dir("io_mtx");
  SparseMatrix A(4, 4);
  Triplets t{{0, 0, 2.0}, {1, 0, -M_PI}, {0, 1, -M_PI}, {3, 3, 1e-300}, {2, 1, 7.0}};
  A.setFromTriplets(t.begin(), t.end());
  write_matrix_market(A, (dir / "a.mtx").string());
  CHECK((read_matrix_market((dir / "a.mtx").string()) - A).norm() == 0.0);
  SparseMatrix S = A;
  S.coeffRef(1, 2) = 7.0;  // make it symmetric
  write_matrix_market(S, (dir / "s.mtx").string(), true);
  CHECK((read_matrix_market((dir / "s.mtx").string()) - S).norm() == 0.0);

  const nlohmann::json j = {{"x", 1.5}, {"list", {1, 2, 3}}, {"s", "a\"b"}};
  write_json(j, (dir / "j.json").string());
  CHECK(read_json((dir / "j.json").string()) == j);
}

TEST_CASE("writers never leave a truncated file: a failed write keeps the old one", "[io]") {
  const auto dir = test::scratch_dir("io_atomic");
  const std::string p = (dir / "m.obj").string();
  write_mesh(test::grid(2), p);
  const auto before = fs::file_size(p);
  CHECK_THROWS_AS(write_vtp(test::grid(2), (dir / "missing-folder" / "x.vtp").string()), IOError);
  SurfaceMesh bad = test::grid(2);
  bad.vertex_data["wrong"] = Eigen::MatrixXd::Zero(3, 1);  // wrong row count: refused before writing
  CHECK_THROWS_AS(write_vtp(bad, (dir / "bad.vtp").string()), InvalidInput);
  CHECK_FALSE(fs::exists(dir / "bad.vtp"));
  CHECK(fs::file_size(p) == before);
  for (const auto& e : fs::directory_iterator(dir)) CHECK(e.path().string().find(".tmp.") == std::string::npos);
}
