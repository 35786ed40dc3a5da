#include <catch2/catch.hpp>

#include <random>

#include <Eigen/Eigenvalues>

#include "fairshape/constraint/constraint.h"
#include "fairshape/energy/energy.h"
#include "fairshape/experiment/components.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/problem/constrained_system.h"
#include "test_support.h"

using namespace fairshape;

namespace {

SparseMatrix hessian(const std::string& name, const SurfaceMesh& m, const std::string& options = "{}") {
  Config cfg(YAML::Load(options), "energy");
  auto e = components().energies.create(name, Backend::Reference, cfg);
  Triplets t;
  e->add_hessian(m, 1.0, t);
  SparseMatrix H(m.n_vertices(), m.n_vertices());
  H.setFromTriplets(t.begin(), t.end());
  return H;
}

Eigen::MatrixXd solve_with_fixed(const SparseMatrix& H, const std::vector<int>& fixed, const Eigen::MatrixXd& values) {
  ConstrainedSystem s{H, Eigen::MatrixXd::Zero(H.rows(), 3), fixed, values};
  const ReducedSystem r = reduce(s);
  Config none;
  auto direct = components().solvers.create("cholesky", Backend::Reference, none);
  Eigen::MatrixXd x;
  direct->analyze(r.A);
  REQUIRE(direct->solve(r.A, r.b, x).termination == Termination::Converged);
  return r.expand(x);
}

}  // namespace

TEST_CASE("energy Hessians are symmetric PSD with constants in the null space", "[energy]") {
  const SurfaceMesh closed = read_mesh(test::data_path("torus_quad.off"));
  const SurfaceMesh tri = test::grid(5, true);
  for (const auto& [name, mesh, opts] : std::vector<std::tuple<std::string, const SurfaceMesh*, std::string>>{
           {"membrane", &closed, "{}"}, {"umbrella_thin_plate", &closed, "{}"}, {"membrane", &tri, "{weights: cotangent}"},
           {"umbrella_thin_plate", &tri, "{}"}}) {
    INFO(name << " " << opts);
    const SparseMatrix H = hessian(name, *mesh, opts);
    CHECK((SparseMatrix(H.transpose()) - H).norm() <= 1e-12 * H.norm());
    CHECK((H * Eigen::VectorXd::Ones(H.rows())).norm() <= 1e-12 * H.norm());
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig{Eigen::MatrixXd(H)};
    CHECK(eig.eigenvalues().minCoeff() >= -1e-10 * eig.eigenvalues().maxCoeff());
  }
}

TEST_CASE("cotangent weights need triangles", "[energy]") {
  CHECK_THROWS_AS(hessian("membrane", test::grid(3), "{weights: cotangent}"), InvalidInput);
}

TEST_CASE("no handle moved means no deformation, a common offset is a translation", "[energy][constraint]") {
  const SurfaceMesh m = test::grid(8, true);
  const SparseMatrix H = hessian("umbrella_thin_plate", m);
  const std::vector<int> fixed{0, 8, 40, 80};
  const Eigen::MatrixXd zero = solve_with_fixed(H, fixed, Eigen::MatrixXd::Zero(4, 3));
  CHECK(zero.norm() <= 1e-12);
  const Eigen::RowVector3d t(0.3, -1.0, 2.0);
  const Eigen::MatrixXd moved = solve_with_fixed(H, fixed, t.replicate(4, 1));
  CHECK((moved.rowwise() - t).norm() <= 1e-9);
}

namespace {
// A constraint as a config block names it, checked like a run does.
std::unique_ptr<Constraint> make_constraint(const std::string& type, const std::string& yaml) {
  Config cfg(YAML::Load(yaml), "constraints[0]");
  auto c = components().constraints.create(type, Backend::Reference, cfg);
  cfg.check_no_unknown_keys();
  return c;
}
}  // namespace

TEST_CASE("constraints: selections, offsets, levels", "[constraint]") {
  const SurfaceMesh m = test::grid(4);
  const LevelMeshes one_level = [&m](int) -> const SurfaceMesh& { return m; };
  DesignConstraints dc;
  std::vector<PointConstraint>& p = dc.points;
  make_constraint("fixed", "{region: {axis: x, from: 0.0, to: 0.1}}")->add_to(one_level, 0, dc);
  CHECK(p.size() == 5);  // the column x = 0
  for (const auto& c : p) CHECK(c.offset == Vec3::Zero());
  p.clear();
  make_constraint("position", "{nearest: [1, 1, 0], offset: [0, 0, 1], on_limit: true}")->add_to(one_level, 0, dc);
  REQUIRE(p.size() == 1);
  CHECK(p[0].vertex == 24);
  CHECK(p[0].offset == Vec3(0, 0, 1));
  CHECK(p[0].on_limit);
  CHECK(p[0].label == "constraints[0]");
  p.clear();
  make_constraint("position", "{vertices: [3], level: 1, offset: [1, 0, 0]}")->add_to(one_level, 2, dc);
  CHECK(p.at(0).level == 1);
  CHECK_THROWS_WITH(make_constraint("fixed", "{vertices: [99]}")->add_to(one_level, 0, dc),
                    Catch::Matchers::Contains("vertex 99 does not exist"));
  CHECK_THROWS_WITH(make_constraint("fixed", "{vertices: [1], level: 3}")->add_to(one_level, 1, dc),
                    Catch::Matchers::Contains("level 3 is not in the hierarchy"));
  CHECK_THROWS_AS(make_constraint("fixed", "{vertices: [1], nearest: [0, 0, 0]}"), InvalidConfig);
  CHECK_THROWS_AS(make_constraint("position", "{vertices: [1], offset: [1, 2]}"), InvalidConfig);
}

TEST_CASE("rigid, normal and curve constraints place what their configs say", "[constraint]") {
  const SurfaceMesh m = test::grid(4);  // 5 × 5 vertices on [0, 1]², spacing 0.25
  const LevelMeshes one_level = [&m](int) -> const SurfaceMesh& { return m; };
  SECTION("rigid: the boundary loop turns about its centroid") {
    DesignConstraints dc;
    make_constraint("rigid", "{boundary_loop_near: [0, 0, 0], rotation: {axis: [0, 0, 1], angle_deg: 90}, translation: [0, 0, 1]}")
        ->add_to(one_level, 0, dc);
    CHECK(dc.points.size() == 16);
    for (const auto& c : dc.points) {
      const Vec3 p = m.position(c.vertex), q = p + c.offset;
      CHECK(q.x() == Approx(0.5 - (p.y() - 0.5)));
      CHECK(q.y() == Approx(0.5 + (p.x() - 0.5)));
      CHECK(q.z() == Approx(1.0));
    }
  }
  SECTION("normal: unit target, selection resolved") {
    DesignConstraints dc;
    make_constraint("normal", "{nearest: [0.5, 0.5, 0], normal: [0, 3, 4]}")->add_to(one_level, 0, dc);
    REQUIRE(dc.normals.size() == 1);
    CHECK(dc.normals[0].vertex == 12);
    CHECK((dc.normals[0].normal - Vec3(0, 0.6, 0.8)).norm() <= 1e-15);
    CHECK_THROWS_AS(make_constraint("normal", "{vertices: [1]}"), InvalidConfig);
    CHECK_THROWS_AS(make_constraint("normal", "{vertices: [1], normal: [0, 0, 0]}"), InvalidConfig);
  }
  SECTION("curve: vertices snapped in order, targets on the moved curve") {
    DesignConstraints dc;
    make_constraint("curve", "{points: [[0, 0.55, 0], [1, 0.55, 0]], translation: [0, 0, 0.2]}")->add_to(one_level, 0, dc);
    REQUIRE(dc.points.size() == 5);  // the row y = 0.5, 0.05 from the curve
    for (std::size_t i = 0; i < 5; ++i) {
      const Vec3 p = m.position(dc.points[i].vertex);
      CHECK(p.y() == Approx(0.5));
      CHECK(p.x() == Approx(0.25 * static_cast<double>(i)));
      // The vertex lands on the translated curve: the snap is part of the deformation.
      CHECK((p + dc.points[i].offset - Vec3(p.x(), 0.55, 0.2)).norm() <= 1e-12);
    }
  }
  SECTION("curve: bad curves are refused with the reason") {
    DesignConstraints dc;
    CHECK_THROWS_WITH(make_constraint("curve", "{points: [[0, 0.5, 0], [1, 0.5, 0.5]]}")->add_to(one_level, 0, dc),
                      Catch::Matchers::Contains("leaves the surface"));
    CHECK_THROWS_WITH(make_constraint("curve", "{points: [[0, 0.375, 0], [1, 0.375, 0]]}")->add_to(one_level, 0, dc),
                      Catch::Matchers::Contains("no level from 0 to 0"));
    CHECK_THROWS_AS(make_constraint("curve", "{points: [[0, 0, 0]]}"), InvalidConfig);
    CHECK_THROWS_AS(make_constraint("curve", "{points: [[0, 0, 0], [1, 1, 0]], target_points: [[0, 0, 0]]}"), InvalidConfig);
    CHECK_THROWS_AS(make_constraint("curve", "{points: [[0, 0, 0], [1, 1, 0]], snap_ratio: 0.9}"), InvalidConfig);
    CHECK_THROWS_AS(make_constraint("rigid", "{vertices: [1], rotation: {axis: [0, 0, 0], angle_deg: 3}}"), InvalidConfig);
  }
}

TEST_CASE("reduce: H_ff and H_fc are H's blocks, whatever the order of the fixed list", "[problem]") {
  // An unsymmetric H (reduce must not assume symmetry), fixed ids unsorted and one listed twice
  // (it couples through its last listing, whose value it takes).
  const int n = 12;
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (i == j || gen() % 3 == 0) dense(i, j) = u(gen);
  const SparseMatrix H = dense.sparseView(0.0, 0.0);
  const std::vector<int> fixed{9, 2, 5, 2};
  Eigen::MatrixXd values(4, 3), g(n, 3);
  for (Eigen::Index i = 0; i < values.size(); ++i) values.data()[i] = u(gen);
  for (Eigen::Index i = 0; i < g.size(); ++i) g.data()[i] = u(gen);
  const ReducedSystem r = reduce(ConstrainedSystem{H, g, fixed, values});
  const std::vector<int> free{0, 1, 3, 4, 6, 7, 8, 10, 11};
  REQUIRE(r.free == free);
  const Eigen::MatrixXd A = r.A, coupling = r.coupling;
  for (std::size_t a = 0; a < free.size(); ++a) {
    for (std::size_t c = 0; c < free.size(); ++c) CHECK(A(a, c) == dense(free[a], free[c]));
    for (std::size_t k = 0; k < fixed.size(); ++k) CHECK(coupling(a, k) == (k == 1 ? 0.0 : dense(free[a], fixed[k])));
  }
  Eigen::MatrixXd last_values = values;
  last_values.row(1).setZero();  // vertex 2's value is its last listing's (row 3)
  Eigen::MatrixXd g_free(free.size(), 3);
  for (std::size_t a = 0; a < free.size(); ++a) g_free.row(a) = g.row(free[a]);
  CHECK((r.b - (g_free - coupling * last_values)).norm() <= 1e-14);
  CHECK(r.A.isCompressed());
}
