// Constraints anywhere on the surface: exact limit evaluation at (face, u, v) as stencils
// (subdivision/limit_evaluation.h), point and normal constraints there, and curves placed as
// limit points (constraint/curve_limit_points.h), met by exact edits.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <random>
#include <sstream>

#include "fairshape/constraint/curve_limit_points.h"
#include "fairshape/constraint/surface_points.h"
#include "fairshape/core/error.h"
#include "fairshape/design/edit_solve.h"
#include "fairshape/energy/local_quadratic.h"
#include "fairshape/experiment/components.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/remesh/remesh.h"
#include "fairshape/subdivision/limit.h"
#include "fairshape/subdivision/subdivider.h"
#include "edit_test_support.h"
#include "test_support.h"

using namespace fairshape;

namespace {

SurfaceMesh cube() {  // every vertex extraordinary (valence 3): every face is irregular
  MatrixX3 V(8, 3);
  for (int i = 0; i < 8; ++i) V.row(i) << (i & 1 ? 1.0 : -1.0), (i & 2 ? 1.0 : -1.0), (i & 4 ? 1.0 : -1.0);
  V(7, 2) = 1.7;  // not symmetric
  return SurfaceMesh::from_polygons(V, {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}});
}

// Test meshes with their rules: a cube (valence 3 everywhere), an open grid (boundary and
// regular faces), level 1 of a pentagonal bipyramid (valence 3, 4, 5 and 10 under
// Catmull-Clark) and the bipyramid itself under Loop (valence 4 and 5).
std::vector<std::tuple<std::string, SurfaceMesh, SubdivisionOptions>> shapes() {
  MatrixX3 V(7, 3);
  for (int i = 0; i < 5; ++i) V.row(i) << std::cos(2 * M_PI * i / 5), std::sin(2 * M_PI * i / 5), 0.15 * (i % 2);
  V.row(5) << 0, 0, 1.3;
  V.row(6) << 0.1, 0, -0.9;
  PolygonList F;
  for (int i = 0; i < 5; ++i) {
    F.push_back({i, (i + 1) % 5, 5});
    F.push_back({(i + 1) % 5, i, 6});
  }
  const SurfaceMesh bipyramid = SurfaceMesh::from_polygons(V, F);
  SubdivisionOptions cc, loop, corner;
  loop.scheme = SchemeType::Loop;
  corner.boundary = BoundaryMode::EdgeAndCorner;
  MatrixX3 G = test::grid(3).positions();
  for (Eigen::Index i = 0; i < G.rows(); ++i) G(i, 2) = 0.3 * std::sin(3 * G(i, 0)) * G(i, 1);
  SurfaceMesh grid = test::grid(3);
  grid.positions() = G;
  return {{"cube", cube(), cc},
          {"grid", grid, cc},
          {"grid edge-and-corner", grid, corner},
          {"bipyramid level 1", subdivide_once(bipyramid, cc, Backend::Optimized), cc},
          {"bipyramid loop", bipyramid, loop}};
}

double sum(const Stencil& s) {
  double t = 0;
  for (const auto& [v, w] : s) t += w;
  return t;
}

// The corners of a face in the evaluator's parameterization.
std::vector<std::array<double, 2>> corner_uv(bool quad) {
  if (quad) return {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  return {{0, 0}, {1, 0}, {0, 1}};
}

// A random (u, v) in the face's domain.
std::array<double, 2> random_uv(std::mt19937& gen, bool quad) {
  std::uniform_real_distribution<double> d(0.0, 1.0);
  double u = d(gen), v = d(gen);
  if (!quad && u + v > 1) { u = 1 - u; v = 1 - v; }
  return {u, v};
}

int closest_row(const MatrixX3& X, const Vec3& p, double* distance) {
  int i = 0;
  *distance = std::sqrt((X.rowwise() - p.transpose()).rowwise().squaredNorm().minCoeff(&i));
  return i;
}

}  // namespace

TEST_CASE("limit stencils: affine invariance, the vertex limits at face corners", "[limit_points]") {
  std::mt19937 gen(7);
  for (const auto& [name, mesh, opt] : shapes()) {
    INFO(name);
    const LimitEvaluator e(mesh, opt);
    const MatrixX3 L = limit_positions(mesh, opt);
    const double size = (mesh.positions().colwise().maxCoeff() - mesh.positions().colwise().minCoeff()).norm();
    const bool quad = opt.scheme == SchemeType::CatmullClark;
    for (int f = 0; f < mesh.n_faces(); ++f) {
      for (int k = 0; k < 3; ++k) {
        const auto [u, v] = random_uv(gen, quad);
        const LimitStencils s = e.stencils({f, u, v});
        CHECK(sum(s.position) == Approx(1.0).margin(1e-12));
        CHECK(std::abs(sum(s.du)) <= 1e-11);
        CHECK(std::abs(sum(s.dv)) <= 1e-11);
        // Derivatives are the stencil's: a finite difference of positions agrees.
        const double h = 1e-6, u0 = std::min(u, 1 - 2 * h - (quad ? 0 : v));
        const Vec3 fd = (e.position({f, u0 + h, v}) - e.position({f, u0, v})) / h;
        const Vec3 du = LimitEvaluator::apply(e.stencils({f, u0 + 0.5 * h, v}).du, mesh.positions());
        CHECK((fd - du).norm() <= 1e-5 * std::max(1.0, du.norm()));
      }
      const auto corners = mesh.face_vertices(f);
      const auto uv = corner_uv(quad);
      for (std::size_t c = 0; c < corners.size(); ++c) {
        const Vec3 p = e.position({f, uv[c][0], uv[c][1]});
        CHECK((p - L.row(corners[c]).transpose()).norm() <= 1e-12 * size);
      }
    }
  }
}

TEST_CASE("limit stencils against uniform refinement: exact at dyadic parameters, converging between", "[limit_points]") {
  std::mt19937 gen(11);
  for (const auto& [name, mesh, opt] : shapes()) {
    INFO(name);
    const LimitEvaluator e(mesh, opt);
    const bool quad = opt.scheme == SchemeType::CatmullClark;
    const double size = (mesh.positions().colwise().maxCoeff() - mesh.positions().colwise().minCoeff()).norm();
    const auto levels = refine_uniform(mesh, opt, 5, Backend::Optimized);
    std::vector<double> error_by_depth;
    for (int depth = 3; depth <= 5; ++depth) {
      const MatrixX3 fine_limit = limit_positions(levels[depth], opt);
      const double h = 1.0 / (1 << depth);
      double worst = 0;
      for (int f = 0; f < mesh.n_faces(); ++f) {
        // A dyadic parameter is a vertex of level `depth`: our limit point must be that
        // vertex's limit (found as the nearest one) to rounding.
        const auto [u, v] = random_uv(gen, quad);
        const double i = std::floor(u / h), j = std::floor(v / h);
        if (!quad && (i + j + 2) * h > 1) continue;  // keep the cell's four corners in the triangle
        Vec3 cell[2][2];
        for (int a = 0; a < 2; ++a)
          for (int b = 0; b < 2; ++b) {
            double d = 0;
            const int r = closest_row(fine_limit, e.position({f, (i + a) * h, (j + b) * h}), &d);
            CHECK(d <= 1e-10 * size);
            cell[a][b] = fine_limit.row(r).transpose();
          }
        // Between them, the bilinear interpolant of the refined surface's limit points tends to
        // ours at rate h²: the error must shrink with depth.
        const double s = u / h - i, t = v / h - j;
        const Vec3 interp = (1 - s) * (1 - t) * cell[0][0] + s * (1 - t) * cell[1][0] + (1 - s) * t * cell[0][1] + s * t * cell[1][1];
        worst = std::max(worst, (interp - e.position({f, u, v})).norm());
      }
      error_by_depth.push_back(worst);
    }
    INFO("interpolation error at depths 3, 4, 5: " << error_by_depth[0] << " " << error_by_depth[1] << " " << error_by_depth[2]);
    CHECK(error_by_depth[2] < error_by_depth[0] / 4);
    CHECK(error_by_depth[2] <= 1e-2 * size);
  }
}

TEST_CASE("closest point on the limit surface recovers a limit point", "[limit_points]") {
  std::mt19937 gen(3);
  for (const auto& [name, mesh, opt] : shapes()) {
    INFO(name);
    const LimitEvaluator e(mesh, opt);
    const double size = (mesh.positions().colwise().maxCoeff() - mesh.positions().colwise().minCoeff()).norm();
    std::uniform_int_distribution<int> face(0, mesh.n_faces() - 1);
    for (int k = 0; k < 10; ++k) {
      const int f = face(gen);
      const auto [u, v] = random_uv(gen, opt.scheme == SchemeType::CatmullClark);
      const Vec3 p = e.position({f, u, v});
      const FaceParameter q = e.closest_point(p);
      CHECK(e.why_not(q).empty());
      CHECK((e.position(q) - p).norm() <= 1e-9 * size);
    }
  }
}

TEST_CASE("a (u, v) outside its face or a missing face is refused, naming the key and the range", "[limit_points]") {
  const MultiresSurface h(test::grid(3), {}, 1, Backend::Optimized);
  const LevelMeshes mesh_at = [&h](int l) -> const SurfaceMesh& { return h.mesh(l); };
  DesignConstraints dc;
  auto place = [&](const std::string& type, const std::string& yaml) {
    Config cfg(YAML::Load(yaml), "constraints[1]");
    components().constraints.create(type, Backend::Optimized, cfg)->add_on_surface(mesh_at, 1, h.options(), dc);
  };
  CHECK_THROWS_WITH(place("position", "{at: {face: 3, uv: [1.5, 0.2]}, offset: [0, 0, 1]}"),
                    Catch::Matchers::Contains("constraints[1].at") && Catch::Matchers::Contains("u = 1.5") &&
                        Catch::Matchers::Contains("[0, 1]"));
  CHECK_THROWS_WITH(place("fixed", "{at: {face: 36, uv: [0.5, 0.5]}}"),
                    Catch::Matchers::Contains("constraints[1].at") && Catch::Matchers::Contains("faces 0..35"));
  CHECK_THROWS_WITH(place("normal", "{at: {face: 0, uv: [0.5, -0.1]}, normal: [0, 0, 1]}"),
                    Catch::Matchers::Contains("v = -0.1"));
  CHECK_THROWS_WITH(place("fixed", "{at: {face: 0, uv: [0.5]}}"), Catch::Matchers::Contains("constraints[1].at.uv"));
  CHECK_THROWS_WITH(place("fixed", "{at: {face: 0, uv: [0.5, 0.5], colour: red}}"), Catch::Matchers::Contains("colour"));
  CHECK_THROWS_WITH(place("fixed", "{at: {face: 0, uv: [0.5, 0.5]}, vertices: [1]}"),
                    Catch::Matchers::Contains("cannot be combined"));
  CHECK_THROWS_WITH(place("fixed", "{nearest_on_limit: [0, 0, 0], on_limit: true}"), Catch::Matchers::Contains("on_limit"));
  CHECK(dc.points.empty());
  place("fixed", "{at: {face: 0, uv: [1, 0], level: 0}}");  // the range is closed
  CHECK(dc.points.size() == 1);
}

namespace {

using test::cholesky;
using test::detail_preserving;

// The finest level after an edit at `edit` (the deformation subdivided up).
MatrixX3 edited_finest(const MultiresSurface& h, int edit, const EditSolution& s) {
  return h.mesh(h.levels()).positions() + MatrixX3(h.prolongation(edit, h.levels()) * s.delta);
}

}  // namespace

TEST_CASE("point and normal constraints at (face, u, v) of the finest level are met by exact edits", "[limit_points][design]") {
  const MultiresSurface h(test::grid(4), {}, 2, Backend::Optimized);
  const LevelMeshes mesh_at = [&h](int l) -> const SurfaceMesh& { return h.mesh(l); };
  const SurfaceMesh& fine = h.mesh(2);
  DesignConstraints dc;
  for (const auto& [type, yaml] : std::vector<std::pair<std::string, std::string>>{
           {"position", "{at: {face: 100, uv: [0.3, 0.7]}, offset: [0.02, -0.01, 0.15]}"},
           {"normal", "{at: {face: 100, uv: [0.3, 0.7]}, normal: [0.3, 0.1, 1]}"},
           {"fixed", "{region: {axis: x, from: 0.0, to: 0.05}}"},
           {"fixed", "{region: {axis: x, from: 0.95, to: 1.0}}"}}) {
    Config cfg(YAML::Load(yaml), "constraints[0]");
    components().constraints.create(type, Backend::Optimized, cfg)->add_on_surface(mesh_at, 2, h.options(), dc);
  }
  REQUIRE(dc.points.front().surface.position.size() >= 9);  // a real stencil, not a vertex
  const FaceParameter at{100, 0.3, 0.7};
  const LimitEvaluator before(fine, h.options());
  const Vec3 rest = before.position(at);
  auto solver = cholesky();
  for (int edit : {0, 1, 2}) {
    INFO("edit level " << edit);
    const EditSolution s = solve_edit(detail_preserving(h, edit, dc), ConstraintMode::Kkt, *solver, Backend::Optimized);
    INFO(s.summary.message);
    REQUIRE(s.summary.termination == Termination::Converged);
    // Evaluate the edited finest level's limit surface at the same (face, u, v).
    SurfaceMesh edited = fine;
    edited.positions() = edited_finest(h, edit, s);
    const LimitEvaluator after(edited, h.options());
    const Vec3 p = after.position(at);
    CHECK((p - (rest + Vec3(0.02, -0.01, 0.15))).norm() <= 1e-10);
    const LimitStencils st = after.stencils(at);
    const Vec3 n = LimitEvaluator::apply(st.du, edited.positions()).cross(LimitEvaluator::apply(st.dv, edited.positions()));
    CHECK(n.normalized().dot(Vec3(0.3, 0.1, 1).normalized()) >= 1 - 1e-10);
  }
}

TEST_CASE("a curve on the finest level of a remeshed cow is met on the limit surface", "[limit_points][design][curve][slow]") {
  RemeshOptions ro;
  ro.base_faces = 200;
  ro.levels = 2;
  const MultiresSurface h = remesh(read_mesh(test::data_path("cow.off")), ro, nullptr);
  const LevelMeshes mesh_at = [&h](int l) -> const SurfaceMesh& { return h.mesh(l); };
  const SurfaceMesh& fine = h.mesh(2);
  const double diagonal = (fine.positions().colwise().maxCoeff() - fine.positions().colwise().minCoeff()).norm();
  {  // Closest points on a real model's limit surface (thin parts: ears, legs) are recovered.
    const LimitEvaluator e(fine, h.options());
    std::mt19937 gen(5);
    std::uniform_int_distribution<int> face(0, fine.n_faces() - 1);
    for (int k = 0; k < 100; ++k) {
      const FaceParameter p{face(gen), std::generate_canonical<double, 53>(gen), std::generate_canonical<double, 53>(gen)};
      const Vec3 x = e.position(p);
      CHECK((e.position(e.closest_point(x)) - x).norm() <= 1e-9 * diagonal);
    }
  }
  // A curve along a path of finest-level edges: control points at the limit positions of its
  // vertices (on the limit surface; the chords between them are close to it).
  const MatrixX3 L = limit_positions(fine, h.options());
  int top = 0;  // start on the back (highest limit point), walk towards the head: away from the fixed rear
  L.col(1).maxCoeff(&top);
  std::vector<int> path{top};
  const Vec3 dir(1, 0, 0);
  while (path.size() < 13) {  // walk the edge most aligned with +x
    int best = -1;
    double score = -1e300;
    for (int w : fine.vertex_neighbors(path.back()))
      if (std::find(path.begin(), path.end(), w) == path.end())
        if (const double sc = (L.row(w) - L.row(path.back())).normalized().dot(dir.transpose()); sc > score) { score = sc; best = w; }
    REQUIRE(best >= 0);
    path.push_back(best);
  }
  std::ostringstream yaml;
  yaml << "{placement: limit_points, translation: [0, 0.02, 0.01], points: [";
  for (std::size_t i = 0; i < path.size(); ++i) yaml << (i ? ", " : "") << "[" << L(path[i], 0) << ", " << L(path[i], 1) << ", " << L(path[i], 2) << "]";
  yaml << "]}";
  Config cfg(YAML::Load(yaml.str()), "constraints[1]");
  DesignConstraints dc;
  components().constraints.create("curve", Backend::Optimized, cfg)->add_on_surface(mesh_at, 2, h.options(), dc);
  REQUIRE(dc.curves.size() == 1);
  const auto& samples = dc.curves.front().samples;
  REQUIRE(samples.size() == dc.points.size());
  CHECK(samples.size() > path.size());  // denser than the polygon
  // (AP) on the limit surface: consecutive points in the same face or faces sharing a vertex.
  for (std::size_t i = 1; i < samples.size(); ++i) {
    const auto& a = samples[i - 1].corners;
    const auto& b = samples[i].corners;
    CHECK(std::any_of(a.begin(), a.end(), [&](int v) { return std::find(b.begin(), b.end(), v) != b.end(); }));
  }
  // The far half of the cow stays.
  Config fixed(YAML::Load("{region: {axis: x, from: 0.0, to: 0.3}}"), "constraints[0]");
  components().constraints.create("fixed", Backend::Optimized, fixed)->add_on_surface(mesh_at, 2, h.options(), dc);
  auto solver = cholesky();
  for (int edit : {2, 1, 0}) {
    INFO("edit level " << edit);
    const EditSolution s = solve_edit(detail_preserving(h, edit, dc), ConstraintMode::Kkt, *solver, Backend::Optimized);
    INFO(s.summary.message);
    // On coarser levels the curve's basis functions may also reach the fixed half (how far
    // depends on the remesh): then the run says the constraints were not met (least-squares
    // fit) or are ill-posed (nearly conflicting), never converged with a wrong answer.
    const Termination t = s.summary.termination;
    const bool said = t == Termination::ConstraintsUnmet || t == Termination::IllConditioned;
    REQUIRE((t == Termination::Converged || (edit < 2 && said)));
    const MatrixX3 X = edited_finest(h, edit, s);
    double worst = 0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const Vec3 target = LimitEvaluator::apply(samples[i].position, fine.positions()) + Vec3(0, 0.02, 0.01);
      worst = std::max(worst, (LimitEvaluator::apply(samples[i].position, X) - target).norm());
    }
    INFO(samples.size() << " curve points, worst distance to target " << worst << ", diagonal " << diagonal);
    // On the finest level every point has unknowns of its own: met exactly.
    CHECK((worst <= 1e-8 * diagonal || (edit < 2 && said)));
  }
}

TEST_CASE("an N-gon of a Catmull-Clark base is refused, naming its quads one level finer", "[limit_points]") {
  // A pentagon between quads: level 0 has a 5-gon, level 1 only quads. The message gives the
  // level-1 quads (0 + i at corner i); there (0, 0) is corner i's limit and (1, 1) the limit
  // of the pentagon's centroid, the same point from all five quads.
  MatrixX3 V(10, 3);
  PolygonList F{{0, 1, 2, 3, 4}};
  for (int i = 0; i < 5; ++i) {
    V.row(i) << std::cos(2 * M_PI * i / 5), std::sin(2 * M_PI * i / 5), 0.1 * (i % 2);
    V.row(5 + i) << 2 * std::cos(2 * M_PI * i / 5), 2 * std::sin(2 * M_PI * i / 5), -0.3;
    F.push_back({i, 5 + i, 5 + (i + 1) % 5, (i + 1) % 5});  // quads around the pentagon
  }
  const MultiresSurface h(SurfaceMesh::from_polygons(V, F), {}, 1, Backend::Optimized);
  const LimitEvaluator coarse(h.mesh(0), h.options());
  const std::string why = coarse.why_not({0, 0.5, 0.5});
  INFO(why);
  CHECK_THAT(why, Catch::Matchers::Contains("face 0 is a 5-gon (valence 5)") && Catch::Matchers::Contains("quads 0..4") &&
                      Catch::Matchers::Contains("one level finer"));
  CHECK(coarse.why_not({1, 0.5, 0.5}).empty());  // a quad of the same level is fine
  CHECK_THROWS_WITH(coarse.closest_point(Vec3::Zero()), Catch::Matchers::Contains("5-gon"));
  const LimitEvaluator fine(h.mesh(1), h.options());
  const MatrixX3 L = limit_positions(h.mesh(0), h.options());
  const Vec3 centre = fine.position({0, 1, 1});
  for (int i = 0; i < 5; ++i) {
    CHECK((fine.position({i, 0, 0}) - L.row(i).transpose()).norm() <= 1e-12);
    CHECK((fine.position({i, 1, 1}) - centre).norm() <= 1e-12);
  }
  // Through the config: the error names the key, the level and the finer address.
  const LevelMeshes mesh_at = [&h](int l) -> const SurfaceMesh& { return h.mesh(l); };
  DesignConstraints dc;
  Config cfg(YAML::Load("{at: {face: 0, uv: [0.2, 0.2], level: 0}, offset: [0, 0, 1]}"), "constraints[1]");
  CHECK_THROWS_WITH(
      components().constraints.create("position", Backend::Optimized, cfg)->add_on_surface(mesh_at, 1, h.options(), dc),
      Catch::Matchers::Contains("constraints[1].at: on level 0: face 0 is a 5-gon"));
}
