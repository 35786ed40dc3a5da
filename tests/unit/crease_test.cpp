// Creases and corners: OpenSubdiv's OBJ tags, their validation, and the subdivision rules
// (classification, decay, fractional blending) checked by properties that would fail under a
// wrong rule. Agreement with OpenSubdiv itself is in conformance/opensubdiv_oracle_test.cpp.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>

#include "fairshape/core/error.h"
#include "fairshape/energy/divided_differences.h"
#include "fairshape/energy/local_quadratic.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/io/vtk_io.h"
#include "fairshape/subdivision/crease_rules.h"
#include "fairshape/subdivision/feature_creases.h"
#include "fairshape/subdivision/multires_surface.h"
#include "fairshape/subdivision/subdivider.h"
#include "test_support.h"

using namespace fairshape;

namespace {

const char* kCube =
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
const int kCubeEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                               {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};

std::string write_text(const std::string& test, const std::string& name, const std::string& text) {
  const auto path = (test::scratch_dir(test) / name).string();
  std::ofstream(path) << text;
  return path;
}

SurfaceMesh cube(const std::string& tags = "") {
  return read_mesh(write_text("crease_cube", "cube.obj", std::string(kCube) + tags));
}

SurfaceMesh triangulated(const SurfaceMesh& m) {
  PolygonList tris;
  for (const auto& f : m.polygons())
    for (std::size_t i = 1; i + 1 < f.size(); ++i) tris.push_back({f[0], f[i], f[i + 1]});
  SurfaceMesh t = SurfaceMesh::from_polygons(m.positions(), tris);
  for (int e = 0; e < m.n_edges(); ++e)
    if (m.edge_sharpness(e) > 0) t.set_edge_sharpness(m.from_vertex(2 * e), m.to_vertex(2 * e), m.edge_sharpness(e));
  for (int v = 0; v < m.n_vertices(); ++v)
    if (m.vertex_sharpness(v) > 0) t.set_vertex_sharpness(v, m.vertex_sharpness(v));
  return t;
}

std::string all_cube_edges(double s) {
  std::string tags;
  for (const auto& e : kCubeEdges)
    tags += "t crease 2/1/0 " + std::to_string(e[0]) + " " + std::to_string(e[1]) + " " + std::to_string(s) + "\n";
  return tags;
}

}  // namespace

TEST_CASE("OBJ crease and corner tags become edge and vertex sharpness", "[io][crease]") {
  const SurfaceMesh m = cube(
      "t crease 2/1/0 0 1 3.0\n"
      "t crease 4/1/0 1 2 2 3 10\n"        // one value for both pairs
      "t crease 4/2/0 4 5 5 6 0.3 0.7\n"   // one value per pair
      "t corner 1/1/0 7 1.4\n"
      "t interpolateboundary 1/0/0 2\n");  // not a sharpness tag: skipped
  CHECK(m.edge_sharpness(m.find_edge(0, 1)) == 3.0f);
  CHECK(m.edge_sharpness(m.find_edge(1, 0)) == 3.0f);  // either direction names the edge
  CHECK(m.edge_sharpness(m.find_edge(1, 2)) == 10.0f);
  CHECK(m.edge_sharpness(m.find_edge(2, 3)) == 10.0f);
  CHECK(m.edge_sharpness(m.find_edge(4, 5)) == 0.3f);
  CHECK(m.edge_sharpness(m.find_edge(5, 6)) == 0.7f);
  CHECK(m.vertex_sharpness(7) == 1.4f);
  int sharp_edges = 0, sharp_vertices = 0;
  for (int e = 0; e < m.n_edges(); ++e) sharp_edges += m.edge_sharpness(e) > 0;
  for (int v = 0; v < m.n_vertices(); ++v) sharp_vertices += m.vertex_sharpness(v) > 0;
  CHECK(sharp_edges == 5);
  CHECK(sharp_vertices == 1);
  const MeshFile raw = parse_obj(std::string(kCube) + "t interpolateboundary 1/0/0 2\n", "mem.obj");
  REQUIRE(raw.warnings.size() == 1);
  CHECK_THAT(raw.warnings[0], Catch::Matchers::Contains("'t interpolateboundary'"));
  CHECK_FALSE(read_mesh(write_text("crease_plain", "plain.obj", kCube)).has_sharpness());
}

TEST_CASE("bad crease and corner tags are errors naming file, line and problem", "[io][crease]") {
  struct Case {
    std::string tag, message;
  } cases[] = {
      {"t crease 2/1/0 0 2 3.0", "no edge between vertices 0 and 2"},  // a face diagonal
      {"t crease 2/1/0 0 99 3.0", "no edge between vertices 0 and 99"},
      {"t crease 2/1/0 0 1 -1", "sharpness must be finite and >= 0"},
      {"t crease 2/1/0 0 1 nan", "sharpness"},
      {"t corner 1/1/0 8 1", "vertex id out of range"},
      {"t crease 2/1/0 0 1", "needs 3 values"},
      {"t crease 3/1/0 0 1 2 1", "2n vertex ids"},
      {"t crease 2/1/0 -1 1 2", "0-based"},
      {"t corner x/1/0 1 1", "integer count"},
  };
  for (const auto& c : cases) {
    INFO(c.tag);
    const std::string path = write_text("crease_bad", "bad.obj", std::string(kCube) + "# a comment\n" + c.tag + "\n");
    try {
      (void)read_mesh(path);
      FAIL("accepted");
    } catch (const ParseError& e) {
      CHECK(e.line() == 16);  // 8 v, 6 f, the comment, then the tag
      CHECK_THAT(e.what(), Catch::Matchers::Contains("bad.obj:16:"));
      CHECK_THAT(e.what(), Catch::Matchers::Contains(c.message));
    }
  }
}

TEST_CASE("sharpness round-trips through OBJ files", "[io][crease]") {
  const SurfaceMesh m = read_mesh(test::source_path("tests/data/osd-shapes/tagged/catmark_cubes_semisharp.obj"));
  REQUIRE(m.has_sharpness());
  const std::string path = (test::scratch_dir("crease_roundtrip") / "m.obj").string();
  write_mesh(m, path);
  const SurfaceMesh r = read_mesh(path);
  REQUIRE(r.n_edges() == m.n_edges());
  for (int e = 0; e < m.n_edges(); ++e)
    CHECK(r.edge_sharpness(r.find_edge(m.from_vertex(2 * e), m.to_vertex(2 * e))) == m.edge_sharpness(e));
  for (int v = 0; v < m.n_vertices(); ++v) CHECK(r.vertex_sharpness(v) == m.vertex_sharpness(v));
}

TEST_CASE("sharpness round-trips through .vtp files, other data arrays untouched", "[io][vtk][crease]") {
  SurfaceMesh m = read_mesh(test::source_path("tests/data/osd-shapes/tagged/catmark_cubes_semisharp.obj"));
  m.vertex_data["weight"] = Eigen::MatrixXd::Constant(m.n_vertices(), 1, 2.0);
  const std::string path = (test::scratch_dir("crease_vtp") / "m.vtp").string();
  write_vtp(m, path);
  const SurfaceMesh r = read_vtp(path);
  REQUIRE(r.n_edges() == m.n_edges());
  for (int e = 0; e < m.n_edges(); ++e)
    CHECK(r.edge_sharpness(r.find_edge(m.from_vertex(2 * e), m.to_vertex(2 * e))) == m.edge_sharpness(e));
  for (int v = 0; v < m.n_vertices(); ++v) CHECK(r.vertex_sharpness(v) == m.vertex_sharpness(v));
  CHECK(r.vertex_data.size() == 1);  // the sharpness array is not left behind as data
  CHECK(r.vertex_data.count("weight") == 1);
  const SurfaceMesh plain = read_vtp((write_vtp(test::grid(2), path), path));
  CHECK_FALSE(plain.has_sharpness());
}

TEST_CASE("vertex rules follow the number of sharp edges and the vertex sharpness", "[subdivision][crease]") {
  CHECK(vertex_rule(0.0f, 0) == VertexRule::Smooth);
  CHECK(vertex_rule(0.0f, 1) == VertexRule::Dart);
  CHECK(vertex_rule(0.0f, 2) == VertexRule::Crease);
  CHECK(vertex_rule(0.0f, 3) == VertexRule::Corner);
  CHECK(vertex_rule(0.5f, 0) == VertexRule::Corner);
  CHECK(decayed_sharpness(2.5f) == 1.5f);
  CHECK(decayed_sharpness(1.0f) == 0.0f);
  CHECK(decayed_sharpness(0.4f) == 0.0f);
  CHECK(decayed_sharpness(10.0f) == 10.0f);
  CHECK(decayed_sharpness(12.0f) == 10.0f);
  // On a cube with the loop 0-1-2-3 sharp, its vertices are creases, the others smooth;
  // sharpening one more edge at vertex 0 makes it a corner.
  SurfaceMesh m = cube("t crease 2/1/0 0 1 10\nt crease 2/1/0 1 2 10\nt crease 2/1/0 2 3 10\nt crease 2/1/0 3 0 10\n");
  for (int v = 0; v < 4; ++v) CHECK(vertex_rule(m, v, BoundaryMode::EdgeOnly) == VertexRule::Crease);
  for (int v = 4; v < 8; ++v) CHECK(vertex_rule(m, v, BoundaryMode::EdgeOnly) == VertexRule::Smooth);
  m.set_edge_sharpness(0, 4, 10);
  CHECK(vertex_rule(m, 0, BoundaryMode::EdgeOnly) == VertexRule::Corner);
  CHECK(vertex_rule(m, 4, BoundaryMode::EdgeOnly) == VertexRule::Dart);
}

TEST_CASE("an infinitely sharp cage subdivides to its own flat faces", "[subdivision][crease]") {
  // Every cube edge infinitely sharp: corners stay, edges stay straight, faces stay flat.
  const SurfaceMesh quads = cube(all_cube_edges(10));
  for (SchemeType scheme : {SchemeType::CatmullClark, SchemeType::Loop})
    for (Backend backend : {Backend::Reference, Backend::Optimized}) {
      INFO(to_string(scheme) << " " << static_cast<int>(backend));
      const SurfaceMesh base = scheme == SchemeType::Loop ? triangulated(quads) : quads;
      const auto levels = refine_uniform(base, {scheme}, 3, backend);
      const SurfaceMesh& fine = levels.back();
      CHECK(fine.has_sharpness());  // infinite sharpness never decays
      for (int v = 0; v < 8; ++v) CHECK((fine.positions().row(v) - base.positions().row(v)).norm() == 0.0);
      for (int v = 0; v < fine.n_vertices(); ++v)
        CHECK(fine.positions().row(v).cwiseAbs().maxCoeff() == Approx(1.0).epsilon(1e-14));
    }
}

TEST_CASE("semi-sharp creases decay by one per level and interpolate between smooth and sharp",
          "[subdivision][crease]") {
  SurfaceMesh m = cube("t crease 2/1/0 0 1 2.5\nt corner 1/1/0 3 1.5\n");
  const auto levels = refine_uniform(m, {}, 3, Backend::Optimized);
  const SurfaceMesh& l1 = levels[1];
  const int e01 = m.find_edge(0, 1);
  CHECK(l1.edge_sharpness(2 * e01) == 1.5f);  // both halves of the parent edge
  CHECK(l1.edge_sharpness(2 * e01 + 1) == 1.5f);
  CHECK(l1.vertex_sharpness(3) == 0.5f);
  CHECK(levels[2].edge_sharpness(2 * (2 * e01)) == 0.5f);
  CHECK(levels[2].vertex_sharpness(3) == 0.0f);
  CHECK_FALSE(levels[3].has_sharpness());
  // The loop 0-1-2-3 (the face z = -1) creased with sharpness s: after 3 levels its points
  // leave the plane less the sharper the crease, and not at all from s = 3 on (sharp rules
  // at every level, the last one a blend with full weight on the sharp side).
  double previous = 1e9;
  for (double s : {0.0, 0.5, 1.0, 2.0, 3.0, 10.0}) {
    SurfaceMesh c = cube();
    for (int i = 0; i < 4; ++i)
      if (s > 0) c.set_edge_sharpness(i, (i + 1) % 4, s);
    const SurfaceMesh fine = refine_uniform(c, {}, 3, Backend::Optimized).back();
    double off_plane = 0;
    for (int i = 0; i < 4; ++i) {
      off_plane = std::max(off_plane, std::abs(fine.position(i).z() + 1.0));
      off_plane = std::max(off_plane, std::abs(fine.position(8 + c.find_edge(i, (i + 1) % 4)).z() + 1.0));
    }
    INFO("s = " << s << ": " << off_plane);
    if (s <= 2.0) CHECK(off_plane < previous);
    if (s >= 3.0) CHECK(off_plane == 0.0);
    previous = off_plane;
  }
}

TEST_CASE("Chaikin's crease method averages semi-sharp edges at a vertex before the decay", "[subdivision][crease][chaikin]") {
  // Edges 0-1 (sharpness 2) and 1-2 (sharpness 1) meet at vertex 1; vertex 0 and 2 have no
  // other semi-sharp edge. Chaikin: at vertex 1, 0-1 becomes 3/4 2 + 1/4 1 - 1 = 0.75 and
  // 1-2 becomes 3/4 1 + 1/4 2 - 1 = 0.25; at their other ends they decay by one (1 and 0).
  // Uniform: 1 and 0 on both halves. An infinitely sharp edge at the vertex takes no part.
  const SurfaceMesh m = cube("t crease 2/1/0 0 1 2\nt crease 2/1/0 1 2 1\nt crease 2/1/0 1 5 10\n");
  const int e01 = m.find_edge(0, 1), e12 = m.find_edge(1, 2);
  CHECK(child_edge_sharpness(m, e01, 1, CreaseMethod::Chaikin) == 0.75f);
  CHECK(child_edge_sharpness(m, e12, 1, CreaseMethod::Chaikin) == 0.25f);
  CHECK(child_edge_sharpness(m, e01, 0, CreaseMethod::Chaikin) == 1.0f);
  CHECK(child_edge_sharpness(m, e12, 2, CreaseMethod::Chaikin) == 0.0f);
  CHECK(child_edge_sharpness(m, e01, 1, CreaseMethod::Uniform) == 1.0f);
  CHECK(child_edge_sharpness(m, m.find_edge(1, 5), 1, CreaseMethod::Chaikin) == kInfiniteSharpness);
  // The child mesh carries the two halves separately (half 2e at from_vertex(2e)).
  SubdivisionOptions chaikin;
  chaikin.crease = CreaseMethod::Chaikin;
  const SurfaceMesh l1 = subdivide_once(m, chaikin, Backend::Optimized);
  const bool forward = m.from_vertex(2 * e01) == 0;
  CHECK(l1.edge_sharpness(2 * e01 + (forward ? 0 : 1)) == 1.0f);
  CHECK(l1.edge_sharpness(2 * e01 + (forward ? 1 : 0)) == 0.75f);
  // Edge 1-2 ends (one half smooth) from sharpness 1: its edge point is the midpoint still.
  CHECK(edge_crease_weight(m, e12, CreaseMethod::Chaikin) == 1.0);
  // The method changes the surface (from level 2 on, where the child sharpness is used) only
  // where semi-sharp edges meet.
  auto level2 = [](const SurfaceMesh& mesh, const SubdivisionOptions& opt) {
    return refine_uniform(mesh, opt, 2, Backend::Optimized).back().positions();
  };
  CHECK((level2(m, chaikin) - level2(m, {})).cwiseAbs().maxCoeff() > 1e-3);
  const SurfaceMesh lone = cube("t crease 2/1/0 0 1 2.5\n");
  CHECK((level2(lone, chaikin) - level2(lone, {})).cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE("fractional sharpness blends the smooth and sharp rules linearly", "[subdivision][crease]") {
  // Below 1, an edge point is (1 - s) smooth + s midpoint, and a corner vertex point
  // (1 - s) smooth + s corner: the level-1 points are affine in s.
  for (SchemeType scheme : {SchemeType::CatmullClark, SchemeType::Loop}) {
    INFO(to_string(scheme));
    auto level1 = [&](double edge_s, double corner_s) {
      SurfaceMesh c = cube();
      if (scheme == SchemeType::Loop) c = triangulated(c);
      if (edge_s > 0) c.set_edge_sharpness(0, 1, edge_s);
      if (corner_s > 0) c.set_vertex_sharpness(6, corner_s);
      return subdivide_once(c, {scheme}, Backend::Reference).positions();
    };
    const MatrixX3 smooth = level1(0, 0), sharp = level1(1, 1);
    for (double s : {0.25, 0.5, 0.75}) {
      const MatrixX3 mixed = level1(s, s);
      const MatrixX3 expected = (1 - s) * smooth + s * sharp;
      CHECK((mixed - expected).cwiseAbs().maxCoeff() <= 1e-15);
    }
  }
}

TEST_CASE("the back ends agree on tagged meshes and untagged meshes are unchanged", "[subdivision][crease]") {
  for (const char* name : {"catmark_cubes_semisharp", "catmark_pyramid_creases1", "catmark_tent_creases1",
                           "catmark_val2_interior", "catmark_chaikin1", "catmark_chaikin2", "loop_cubes_semisharp",
                           "loop_triangle_edgeonly", "loop_chaikin1"}) {
    const SurfaceMesh m = read_mesh(test::source_path(std::string("tests/data/osd-shapes/tagged/") + name + ".obj"));
    const SchemeType scheme = std::string(name).rfind("loop", 0) == 0 ? SchemeType::Loop : SchemeType::CatmullClark;
    for (CreaseMethod method : {CreaseMethod::Uniform, CreaseMethod::Chaikin})
    for (BoundaryMode b : {BoundaryMode::EdgeOnly, BoundaryMode::EdgeAndCorner}) {
      INFO(name << " " << to_string(b) << " " << to_string(method));
      const SubdivisionOptions opt{scheme, b, LoopWeights::Loop, method};
      const SparseMatrix ref = make_subdivider(Backend::Reference)->refine(m, opt).S;
      const SparseMatrix fast = make_subdivider(Backend::Optimized)->refine(m, opt).S;
      CHECK((ref - fast).norm() <= 1e-14 * ref.norm());
      MatrixX3 Y;
      subdivide_positions_matrix_free(m, opt, m.positions(), Y);
      CHECK((Y - MatrixX3(ref * m.positions())).norm() <= 1e-13 * Y.norm());
      const Eigen::VectorXd ones = Eigen::VectorXd::Ones(m.n_vertices());
      CHECK((ref * ones - Eigen::VectorXd::Ones(ref.rows())).cwiseAbs().maxCoeff() <= 1e-14);
    }
  }
  // Zero sharpness everywhere is the untagged mesh, to the last bit, in every back end.
  const SurfaceMesh plain = read_mesh(test::data_path("mushroom.off"));
  SurfaceMesh zeros = plain;
  zeros.set_edge_sharpness(plain.from_vertex(0), plain.to_vertex(0), 0.0);
  zeros.set_vertex_sharpness(0, 0.0);
  REQUIRE(zeros.has_sharpness());
  for (Backend backend : {Backend::Reference, Backend::Optimized}) {
    SparseMatrix a, b;
    const SurfaceMesh fa = subdivide_once(plain, {}, backend, &a), fb = subdivide_once(zeros, {}, backend, &b);
    CHECK((fa.positions() - fb.positions()).cwiseAbs().maxCoeff() == 0.0);
    CHECK((a - b).cwiseAbs().sum() == 0.0);
  }
  MatrixX3 ya, yb;
  subdivide_positions_matrix_free(plain, {}, plain.positions(), ya);
  subdivide_positions_matrix_free(zeros, {}, zeros.positions(), yb);
  CHECK((ya - yb).cwiseAbs().maxCoeff() == 0.0);
}

namespace {

// A 4 x 4 quad grid folded along x = 0.5 by `angle` (radians), the fold line tagged
// infinitely sharp when `tagged`: two flat halves meeting at a crease.
SurfaceMesh folded_sheet(double angle, bool tagged) {
  SurfaceMesh m = test::grid(4);
  for (int v = 0; v < m.n_vertices(); ++v) {
    const double x = m.positions()(v, 0) - 0.5;
    if (x > 0) m.positions().row(v) << 0.5 + x * std::cos(angle), m.positions()(v, 1), x * std::sin(angle);
  }
  if (tagged)
    for (int j = 0; j < 4; ++j) m.set_edge_sharpness(5 * j + 2, 5 * (j + 1) + 2, 10.0);
  return m;
}

double quadratic_form(const SparseMatrix& H, const MatrixX3& X) {
  double e = 0;
  for (int c = 0; c < 3; ++c) e += 0.5 * X.col(c).dot(H * X.col(c));
  return e;
}

}  // namespace

TEST_CASE("the bending energy does not fit across a sharp crease", "[energy][crease]") {
  // Bending only (α = 0): a sheet folded flat on both sides of a sharp crease has none (up to
  // rounding: 1e-14 of the untagged fold's in practice), and
  // an edit that swings one side about the crease (both sides stay planar) costs none either;
  // the same fold without the tag is bent (the fits reach across it).
  const StretchBendWeights bend{0.0, 1.0};
  for (Backend backend : {Backend::Reference, Backend::Optimized}) {
    const SurfaceMesh creased = folded_sheet(M_PI / 2, true), smooth = folded_sheet(M_PI / 2, false);
    const SparseMatrix Hc = stretch_bend_hessian(creased, bend, backend);
    const SparseMatrix Hs = stretch_bend_hessian(smooth, bend, backend);
    const double e_smooth = quadratic_form(Hs, smooth.positions());
    INFO(std::scientific << "untagged " << e_smooth << ", tagged " << quadratic_form(Hc, creased.positions()));
    CHECK(e_smooth > 1.0);
    CHECK(quadratic_form(Hc, creased.positions()) <= 1e-12 * e_smooth);
    const MatrixX3 edit = folded_sheet(M_PI / 3, true).positions() - creased.positions();
    CHECK(edit.norm() > 0.5);
    CHECK(quadratic_form(Hc, edit) <= 1e-12 * e_smooth);
    CHECK(quadratic_form(Hs, edit) > 1e-3 * e_smooth);
    CHECK((Hc - stretch_bend_hessian(creased, bend, Backend::Reference)).norm() <= 1e-12 * Hc.norm());
  }
  // Away from the crease nothing changes: the fits of vertices not on it are the same.
  const SurfaceMesh creased = folded_sheet(M_PI / 2, true);
  const auto fits = sector_fits(creased, 5 * 2 + 2);  // an interior crease vertex: two sectors
  REQUIRE(fits.size() == 2);
  CHECK(fits[0].weight == 0.5);
  CHECK(sector_fits(creased, 5 * 2 + 0).size() == 1);
  CHECK(sector_fits(creased, 2).size() == 2);  // on the boundary: the crease splits the fan
}

TEST_CASE("detail frames on a sharp cage use the crease normals", "[subdivision][multires][crease]") {
  // All cube edges infinitely sharp: the surface is the cube itself. Frame normals are the
  // face normal inside a face, the bisector of the two faces on an edge, the mean of three
  // at a corner, pointing outwards (the faces face out).
  for (SchemeType scheme : {SchemeType::CatmullClark, SchemeType::Loop}) {
    INFO(to_string(scheme));
    SurfaceMesh base = cube(all_cube_edges(10));
    if (scheme == SchemeType::Loop) base = triangulated(base);
    const SurfaceMesh fine = refine_uniform(base, {scheme}, 2, Backend::Optimized).back();
    const Frames frames = local_frames(fine, {scheme});
    int on_faces = 0, on_edges = 0, corners = 0;
    for (int v = 0; v < fine.n_vertices(); ++v) {
      const Vec3 p = fine.position(v), n = frames.n.row(v).transpose();
      Vec3 expected = Vec3::Zero();
      for (int k = 0; k < 3; ++k)
        if (std::abs(std::abs(p[k]) - 1.0) < 1e-12) expected[k] = p[k] > 0 ? 1.0 : -1.0;
      const int sides = static_cast<int>(expected.cwiseAbs().sum());
      (sides == 1 ? on_faces : sides == 2 ? on_edges : corners)++;
      INFO("vertex " << v << " at " << p.transpose() << " normal " << n.transpose());
      CHECK((n - expected.normalized()).norm() <= 1e-12);
      CHECK(std::abs(n.dot(frames.t1.row(v).transpose())) <= 1e-12);
    }
    CHECK(corners == 8);
    CHECK(on_edges > 0);
    CHECK(on_faces > 0);
  }
}

TEST_CASE("feature-angle detection marks sharp edges and their corners", "[subdivision][crease]") {
  // A cube: every edge at 90 degrees, every corner joins three.
  SurfaceMesh c = cube();
  CHECK(dihedral_angle_degrees(c, c.find_edge(0, 1)) == Approx(90.0).epsilon(1e-12));
  DetectedCreases found = mark_feature_creases(c, 45.0);
  CHECK(found.edges == 12);
  CHECK(found.corners == 8);
  for (int v = 0; v < 8; ++v) CHECK(vertex_rule(c, v, BoundaryMode::EdgeOnly) == VertexRule::Corner);
  SurfaceMesh none = cube();
  CHECK(mark_feature_creases(none, 91.0).edges == 0);
  CHECK_FALSE(none.has_sharpness());
  // The folded sheet: the four fold edges, no corners inside (each fold vertex has two);
  // the fold's two ends lie on the boundary, where the boundary rules already pin them.
  SurfaceMesh fold = folded_sheet(M_PI / 3, false);
  found = mark_feature_creases(fold, 30.0);
  CHECK(found.edges == 4);
  CHECK(found.corners == 0);
  for (int j = 0; j < 4; ++j) CHECK(fold.edge_sharpness(fold.find_edge(5 * j + 2, 5 * (j + 1) + 2)) == kInfiniteSharpness);
  CHECK(mark_feature_creases(fold, 61.0).edges == 0);  // the fold's 60 degrees stay below
  // A valley that fades out inside the sheet (deep at y = 0, flat from y = 0.5 on): the
  // feature line along x = 0.5 ends at an interior vertex, which becomes a corner. Whatever
  // is detected, interior vertices with one or three or more sharp edges are corners, the
  // others not.
  SurfaceMesh valley = test::grid(8);
  for (int v = 0; v < valley.n_vertices(); ++v) {
    const double x = valley.positions()(v, 0), y = valley.positions()(v, 1);
    valley.positions()(v, 2) = 4.0 * std::abs(x - 0.5) * std::max(0.0, 0.5 - y);
  }
  found = mark_feature_creases(valley, 10.0);
  CHECK(found.edges > 0);
  CHECK(found.corners > 0);
  for (int v = 0; v < valley.n_vertices(); ++v) {
    if (valley.is_boundary_vertex(v)) continue;
    int sharp = 0;
    valley.for_each_outgoing(v, [&](int h) { sharp += valley.edge_sharpness(SurfaceMesh::edge(h)) > 0; });
    INFO("vertex " << v << " with " << sharp << " sharp edges");
    CHECK((valley.vertex_sharpness(v) == kInfiniteSharpness) == (sharp == 1 || sharp > 2));
  }
  CHECK_THROWS_WITH(mark_feature_creases(fold, 0.0), Catch::Matchers::Contains("(0, 180)"));
  CHECK_THROWS_WITH(mark_feature_creases(fold, 180.0), Catch::Matchers::Contains("(0, 180)"));
}
