// Surface points on creased meshes: the limit evaluator (OpenSubdiv Bfr) is given the crease
// and corner tags and the crease method, so it evaluates the same surface the subdivision
// back ends refine. Checked against fairshape's own crease-aware limit positions (at face
// corners, and at dyadic parameters through uniform refinement) on OpenSubdiv's tagged
// regression shapes. Normal constraints at a vertex on a sharp crease are refused in favour
// of one side's surface point (constraint/crease_normals.h).
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <regex>

#include "fairshape/constraint/surface_points.h"
#include "fairshape/core/error.h"
#include "fairshape/design/multires_constraints.h"
#include "fairshape/experiment/components.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/subdivision/crease_rules.h"
#include "fairshape/subdivision/limit.h"
#include "fairshape/subdivision/limit_evaluation.h"
#include "fairshape/subdivision/multires_surface.h"
#include "fairshape/subdivision/subdivider.h"
#include "test_support.h"

using namespace fairshape;

namespace {

SurfaceMesh tagged_shape(const std::string& name) {
  return read_mesh(test::source_path("tests/data/osd-shapes/tagged/" + name + ".obj"));
}

SubdivisionOptions rules_for(const std::string& name, CreaseMethod method = CreaseMethod::Uniform) {
  SubdivisionOptions opt;
  opt.scheme = name.rfind("loop", 0) == 0 ? SchemeType::Loop : SchemeType::CatmullClark;
  opt.crease = method;
  return opt;
}

// Catmull-Clark surface points are given on quads: level 1 of a Catmull-Clark shape (its
// sharpness decayed into it), the shape itself under Loop.
SurfaceMesh evaluation_level(const SurfaceMesh& shape, const SubdivisionOptions& opt) {
  return opt.scheme == SchemeType::Loop ? shape : subdivide_once(shape, opt, Backend::Optimized);
}

double model_size(const SurfaceMesh& m) {
  return (m.positions().colwise().maxCoeff() - m.positions().colwise().minCoeff()).norm();
}

// (u, v) of the point at fraction t along side i of a face (corner i to corner i + 1), in the
// evaluator's parameterization (limit_evaluation.h).
FaceParameter on_side(int face, int side, int corners, double t) {
  if (corners == 4) {
    switch (side) {
      case 0: return {face, t, 0};
      case 1: return {face, 1, t};
      case 2: return {face, 1 - t, 1};
      default: return {face, 0, 1 - t};
    }
  }
  switch (side) {
    case 0: return {face, t, 0};
    case 1: return {face, 1 - t, t};
    default: return {face, 0, 1 - t};
  }
}

double nearest_distance(const MatrixX3& X, const Vec3& p, int* row = nullptr) {
  int i = 0;
  const double d = std::sqrt((X.rowwise() - p.transpose()).rowwise().squaredNorm().minCoeff(&i));
  if (row) *row = i;
  return d;
}

}  // namespace

TEST_CASE("on tagged shapes, limit points at face corners are the crease-aware vertex limits",
          "[limit_points][crease]") {
  // Infinitely sharp and semi-sharp creases, corners, both schemes, both crease methods.
  // Where the vertex limit masks are exact (vertex_limit_mask_exact) Bfr's corner point equals
  // limit_positions to 1e-12. Elsewhere (darts, semi-sharp features not yet decayed) the masks
  // — fairshape's and OpenSubdiv's Far Limit(), which agree — approximate; Bfr refines the
  // sharp features away and is the limit of uniform refinement: the same vertex's limit three
  // levels finer (once the semi-sharp tags have decayed) is nearer to it.
  const std::vector<std::pair<std::string, CreaseMethod>> cases = {
      {"catmark_cube_creases2", CreaseMethod::Uniform},   {"catmark_cubes_semisharp", CreaseMethod::Uniform},
      {"catmark_single_crease", CreaseMethod::Uniform},   {"catmark_torus_creases1", CreaseMethod::Uniform},
      {"catmark_cube_corner2", CreaseMethod::Uniform},    {"catmark_chaikin1", CreaseMethod::Uniform},
      {"catmark_chaikin1", CreaseMethod::Chaikin},        {"catmark_chaikin2", CreaseMethod::Chaikin},
      {"catmark_cubes_semisharp", CreaseMethod::Chaikin}, {"loop_icos_infsharp", CreaseMethod::Uniform},
      {"loop_cubes_semisharp", CreaseMethod::Uniform},    {"loop_chaikin1", CreaseMethod::Chaikin}};
  double worst_exact = 0, worst_coarse = 0, worst_fine = 0;
  int exact_vertices = 0, approximate_vertices = 0;
  for (const auto& [name, method] : cases) {
    INFO(name << " " << to_string(method));
    const SubdivisionOptions opt = rules_for(name, method);
    const SurfaceMesh mesh = evaluation_level(tagged_shape(name), opt);
    REQUIRE(mesh.has_sharpness());
    const LimitEvaluator e(mesh, opt);
    // Finer until the semi-sharp tags have decayed (each level lowers the largest finite
    // sharpness by at least one, Chaikin's average included), at least 3, at most 5 levels.
    float sharpest = 0;
    for (const auto* a : {&mesh.edge_sharpness_array(), &mesh.vertex_sharpness_array()})
      for (float x : *a)
        if (x < kInfiniteSharpness) sharpest = std::max(sharpest, x);
    const int kFiner = std::clamp(static_cast<int>(std::ceil(sharpest)), 3, 5);
    const auto levels = refine_uniform(mesh, opt, kFiner, Backend::Optimized);
    const MatrixX3 L = limit_positions(mesh, opt), L_fine = limit_positions(levels.back(), opt);
    const double size = model_size(mesh);
    double exact = 0, coarse_mask = 0, fine_mask = 0;
    for (int f = 0; f < mesh.n_faces(); ++f) {
      const auto corners = mesh.face_vertices(f);
      const int n = static_cast<int>(corners.size());
      for (int c = 0; c < n; ++c) {
        const int v = corners[c];
        const Vec3 p = e.position(on_side(f, c, n, 0.0));
        const double d = (p - L.row(v).transpose()).norm();
        if (vertex_limit_mask_exact(mesh, v)) {
          exact = std::max(exact, d);
          ++exact_vertices;
        } else {
          coarse_mask = std::max(coarse_mask, d);
          fine_mask = std::max(fine_mask, (p - L_fine.row(v).transpose()).norm());  // vertex ids nest
          ++approximate_vertices;
        }
      }
    }
    INFO(kFiner << " levels finer; exact-mask vertices off by " << exact << "; approximate masks off by " << coarse_mask << ", "
                                       << ", finer by " << fine_mask);
    CHECK(exact <= 1e-12 * size);
    CHECK(fine_mask <= 0.5 * coarse_mask);
    worst_exact = std::max(worst_exact, exact / size);
    worst_coarse = std::max(worst_coarse, coarse_mask / size);
    worst_fine = std::max(worst_fine, fine_mask / size);
    // The tags matter here: evaluated without them, some face corner moves visibly.
    SurfaceMesh untagged = mesh;
    untagged.set_sharpness({}, {});
    const LimitEvaluator smooth(untagged, opt);
    double moved = 0;
    for (int f = 0; f < mesh.n_faces(); ++f)
      for (int c = 0; c < mesh.face_size(f); ++c) {
        const FaceParameter p = on_side(f, c, mesh.face_size(f), 0.0);
        moved = std::max(moved, (smooth.position(p) - e.position(p)).norm());
      }
    CHECK(moved > 1e-4 * size);
  }
  std::cout << "Bfr on tagged shapes: " << exact_vertices << " face corners at exact-mask vertices within "
            << worst_exact << " of the size; " << approximate_vertices
            << " at darts or undecayed semi-sharp features: masks off by up to " << worst_coarse << ", finer levels' by "
            << worst_fine << "\n";
}

TEST_CASE("points along an infinitely sharp crease lie on the limit crease curve", "[limit_points][crease]") {
  // At dyadic u the limit point on a crease edge is a vertex of a finer level: it must be
  // that vertex's crease-aware limit (to rounding). Between dyadic values the point must lie
  // on the refined crease polyline to O(h²), and away from the smooth surface's point.
  for (const char* name : {"catmark_inf_crease1", "catmark_cubes_infsharp", "loop_icos_infsharp"}) {
    INFO(name);
    const SubdivisionOptions opt = rules_for(name);
    const SurfaceMesh mesh = evaluation_level(tagged_shape(name), opt);
    const LimitEvaluator e(mesh, opt);
    constexpr int kDepth = 4;
    const auto levels = refine_uniform(mesh, opt, kDepth, Backend::Optimized);
    const MatrixX3 fine_limit = limit_positions(levels.back(), opt);
    const double size = model_size(mesh), h = 1.0 / (1 << kDepth);
    SurfaceMesh untagged = mesh;
    untagged.set_sharpness({}, {});
    const LimitEvaluator smooth(untagged, opt);
    int crease_sides = 0;
    double worst_dyadic = 0, worst_between = 0, off_smooth = 0;
    for (int f = 0; f < mesh.n_faces(); ++f) {
      const auto corners = mesh.face_vertices(f);
      const int n = static_cast<int>(corners.size());
      for (int side = 0; side < n; ++side) {
        const int edge = mesh.find_edge(corners[side], corners[(side + 1) % n]);
        if (mesh.is_boundary_edge(edge) || mesh.edge_sharpness(edge) < kInfiniteSharpness) continue;
        ++crease_sides;
        std::vector<Vec3> polyline;
        for (int k = 0; k <= (1 << kDepth); ++k) {
          const Vec3 p = e.position(on_side(f, side, n, k * h));
          int row = 0;
          const double d = nearest_distance(fine_limit, p, &row);
          // Interior dyadic points are crease vertices of the fine level (exact masks); the
          // ends are the edge's own vertices, which may be darts (vertex_limit_mask_exact).
          if (k > 0 && k < (1 << kDepth)) worst_dyadic = std::max(worst_dyadic, d);
          polyline.push_back(k > 0 && k < (1 << kDepth) ? Vec3(fine_limit.row(row).transpose()) : p);
        }
        for (double t : {0.3, 0.55, 0.81}) {
          const Vec3 p = e.position(on_side(f, side, n, t));
          const int k = static_cast<int>(t / h);
          const Vec3 a = polyline[k], b = polyline[k + 1];
          const double s = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
          worst_between = std::max(worst_between, (p - (a + s * (b - a))).norm());
          off_smooth = std::max(off_smooth, (p - smooth.position(on_side(f, side, n, t))).norm());
        }
      }
    }
    INFO("crease sides " << crease_sides << ", dyadic " << worst_dyadic << ", between " << worst_between
                         << ", untagged surface off by " << off_smooth);
    CHECK(crease_sides > 0);
    CHECK(worst_dyadic <= 1e-12 * size);
    CHECK(worst_between <= 2e-3 * size);  // the chord error of the depth-4 polyline
    CHECK(off_smooth > 1e-2 * size);
  }
}

namespace {

// A sheet folded along x = 0 into two planes, z = 0.8 |x|, the fold an infinitely sharp
// crease: each side's limit surface stays in its plane, so its one-sided normal is known.
SurfaceMesh folded_sheet() {
  MatrixX3 V(25, 3);
  PolygonList F;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) V.row(5 * j + i) << i - 2.0, j - 2.0, 0.8 * std::abs(i - 2.0);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) F.push_back({5 * j + i, 5 * j + i + 1, 5 * (j + 1) + i + 1, 5 * (j + 1) + i});
  SurfaceMesh m = SurfaceMesh::from_polygons(V, F);
  for (int j = 0; j < 4; ++j) m.set_edge_sharpness(5 * j + 2, 5 * (j + 1) + 2, 10);
  return m;
}

}  // namespace

TEST_CASE("a normal at a vertex on a sharp crease is refused, naming each side's surface point",
          "[limit_points][crease][design]") {
  const MultiresSurface h(folded_sheet(), {}, 1, Backend::Optimized);
  DesignConstraints dc;
  dc.points.push_back({0, 0, false, Vec3::Zero(), "constraints[0]"});
  dc.normals.push_back({0, 12, Vec3::UnitZ(), "constraints[1]"});  // vertex 12: the fold's middle
  std::string message;
  try {
    check_constraints(h, 0, dc);
  } catch (const InvalidInput& e) {
    message = e.what();
  }
  INFO(message);
  CHECK_THAT(message, Catch::Matchers::Contains("constraints[1]: vertex 12 of level 0 is on a sharp crease") &&
                          Catch::Matchers::Contains("side 1 (faces") && Catch::Matchers::Contains("side 2 (faces"));
  // The suggested surface points are the vertex on a face of each side; a normal there is
  // that side's plane normal (±), one per side.
  const std::regex at(R"(at: \{face: (\d+), uv: \[(\d), (\d)\], level: 0\})");
  const LimitEvaluator e(h.mesh(0), h.options());
  std::vector<Vec3> side_normals;
  for (auto it = std::sregex_iterator(message.begin(), message.end(), at); it != std::sregex_iterator(); ++it) {
    const FaceParameter p{std::stoi((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3])};
    CHECK((e.position(p) - h.mesh(0).position(12)).norm() <= 1e-12);  // the vertex (on the crease: interpolated)
    const LimitStencils s = e.stencils(p);
    const Vec3 du = LimitEvaluator::apply(s.du, h.mesh(0).positions()), dv = LimitEvaluator::apply(s.dv, h.mesh(0).positions());
    side_normals.push_back(du.cross(dv).normalized());
  }
  REQUIRE(side_normals.size() == 2);
  const Vec3 left = Vec3(0.8, 0, 1).normalized(), right = Vec3(-0.8, 0, 1).normalized();
  for (const Vec3& n : side_normals) CHECK(std::max(std::abs(n.dot(left)), std::abs(n.dot(right))) >= 1 - 1e-12);
  CHECK(std::abs(side_normals[0].dot(side_normals[1])) < 0.5);  // the two sides, not one twice
  // On the boundary (vertex 2, where the fold meets the sheet's edge) the hole separates the
  // sides as the crease does: one face each.
  dc.normals = {{0, 2, Vec3::UnitZ(), "constraints[1]"}};
  CHECK_THROWS_WITH(check_constraints(h, 0, dc), Catch::Matchers::Contains("(faces 1)") &&
                                                     Catch::Matchers::Contains("(faces 2)") &&
                                                     !Catch::Matchers::Contains("side 3"));
  // A normal constraint given that way is accepted; so is one off the crease.
  dc.normals.clear();
  auto [level, sp] = SurfacePointSelection::at(0, {5, 1, 1}).resolve([&h](int l) -> const SurfaceMesh& { return h.mesh(l); },
                                                                     1, h.options(), "constraints[1]");
  dc.normals.push_back({level, 12, left, "constraints[1]", sp});
  dc.normals.push_back({0, 6, left, "constraints[2]"});
  CHECK_NOTHROW(check_constraints(h, 0, dc));
  // A normal at a point a closest-point search finds on the crease has no side: refused too.
  const LevelMeshes mesh_at = [&h](int l) -> const SurfaceMesh& { return h.mesh(l); };
  auto normal_nearest = [&](const std::string& point) {
    Config cfg(YAML::Load("{nearest_on_limit: " + point + ", level: 0, normal: [0, 0, 1]}"), "constraints[1]");
    DesignConstraints placed;
    components().constraints.create("normal", Backend::Optimized, cfg)->add_on_surface(mesh_at, 1, h.options(), placed);
    return placed.normals.size();
  };
  CHECK_THROWS_WITH(normal_nearest("[0, 0.3, 0]"), Catch::Matchers::Contains("lies on the sharp crease edge") &&
                                                      Catch::Matchers::Contains("constraints[1]"));
  CHECK_THROWS_WITH(normal_nearest("[0, 0, 0]"), Catch::Matchers::Contains("vertex 12 of level 0 is on a sharp crease"));
  CHECK(normal_nearest("[-1.2, 0.3, 0.96]") == 1);  // off the crease
  // A dart (one sharp edge into a smooth vertex) keeps the whole-ring fit.
  SurfaceMesh dart = folded_sheet();
  dart.set_sharpness({}, {});
  dart.set_edge_sharpness(12, 17, 10);
  const MultiresSurface hd(dart, {}, 1, Backend::Optimized);
  dc.normals = {{0, 12, Vec3::UnitZ(), "constraints[1]"}};
  CHECK_NOTHROW(check_constraints(hd, 0, dc));
}


TEST_CASE("on_limit at a semi-sharp corner is the limit the hierarchy converges to", "[limit_points][crease]") {
  // catmark_cube_corner2: vertex 0 carries corner sharpness 2.8. Its level-0 mask (the corner
  // rule) is not its limit; three levels finer the tag has decayed and the mask is exact. The
  // on_limit constraint there becomes a surface point (Bfr) with that limit; a vertex without
  // sharp features keeps its mask row.
  const SurfaceMesh shape = tagged_shape("catmark_cube_corner2");
  REQUIRE(shape.vertex_sharpness(0) == 2.8f);
  const MultiresSurface h(shape, {}, 3, Backend::Optimized);
  const LevelMeshes mesh_at = [&h](int l) -> const SurfaceMesh& { return h.mesh(l); };
  Config cfg(YAML::Load("{vertices: [0, 6], level: 0, on_limit: true, offset: [0, 0, 0.1]}"), "constraints[1]");
  DesignConstraints placed;
  components().constraints.create("position", Backend::Optimized, cfg)->add_on_surface(mesh_at, 3, h.options(), placed);
  REQUIRE(placed.points.size() == 2);
  const PointConstraint& sharp = placed.points[0];
  const PointConstraint& plain = placed.points[1];
  REQUIRE_FALSE(sharp.surface.empty());
  CHECK(marked_vertices(sharp) == std::vector<int>{0});
  CHECK(plain.surface.empty());
  CHECK(plain.on_limit);
  const Vec3 exact = LimitEvaluator::apply(sharp.surface.position, h.mesh(0).positions());
  const double size = model_size(h.mesh(0));
  const MatrixX3 coarse = limit_positions(h.mesh(0), h.options()), fine = limit_positions(h.mesh(3), h.options());
  INFO("level-0 mask off by " << (exact - coarse.row(0).transpose()).norm() << ", level-3 mask by "
                              << (exact - fine.row(0).transpose()).norm());
  CHECK((exact - fine.row(0).transpose()).norm() <= 1e-12 * size);
  CHECK((exact - coarse.row(0).transpose()).norm() > 1e-3 * size);
  CHECK((fine.row(6) - coarse.row(6)).norm() <= 1e-12 * size);  // vertex 6: exact at every level
  CHECK_NOTHROW(check_constraints(h, 0, placed));
}
