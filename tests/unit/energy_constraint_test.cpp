#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>

#include "constraint/constraint.h"
#include "energy/energy.h"
#include "experiment/components.h"
#include "io/mesh_io.h"
#include "problem/constrained_system.h"
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
           {"membrane", &closed, "{}"}, {"thin_plate", &closed, "{}"}, {"membrane", &tri, "{weights: cotangent}"},
           {"thin_plate", &tri, "{}"}}) {
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
  const SparseMatrix H = hessian("thin_plate", m);
  const std::vector<int> fixed{0, 8, 40, 80};
  const Eigen::MatrixXd zero = solve_with_fixed(H, fixed, Eigen::MatrixXd::Zero(4, 3));
  CHECK(zero.norm() <= 1e-12);
  const Eigen::RowVector3d t(0.3, -1.0, 2.0);
  const Eigen::MatrixXd moved = solve_with_fixed(H, fixed, t.replicate(4, 1));
  CHECK((moved.rowwise() - t).norm() <= 1e-9);
}

TEST_CASE("constraints: selections, offsets, levels", "[constraint]") {
  const SurfaceMesh m = test::grid(4);
  const LevelMeshes one_level = [&m](int) -> const SurfaceMesh& { return m; };
  auto make = [](const std::string& type, const std::string& yaml) {
    Config cfg(YAML::Load(yaml), "constraints[0]");
    auto c = components().constraints.create(type, Backend::Reference, cfg);
    cfg.check_no_unknown_keys();
    return c;
  };
  std::vector<PointConstraint> p;
  make("fixed", "{region: {axis: x, from: 0.0, to: 0.1}}")->add_points(one_level, 0, p);
  CHECK(p.size() == 5);  // the column x = 0
  for (const auto& c : p) CHECK(c.offset == Vec3::Zero());
  p.clear();
  make("position", "{nearest: [1, 1, 0], offset: [0, 0, 1], on_limit: true}")->add_points(one_level, 0, p);
  REQUIRE(p.size() == 1);
  CHECK(p[0].vertex == 24);
  CHECK(p[0].offset == Vec3(0, 0, 1));
  CHECK(p[0].on_limit);
  CHECK(p[0].label == "constraints[0]");
  p.clear();
  make("position", "{vertices: [3], level: 1, offset: [1, 0, 0]}")->add_points(one_level, 2, p);
  CHECK(p.at(0).level == 1);
  CHECK_THROWS_WITH(make("fixed", "{vertices: [99]}")->add_points(one_level, 0, p),
                    Catch::Matchers::Contains("vertex 99 does not exist"));
  CHECK_THROWS_WITH(make("fixed", "{vertices: [1], level: 3}")->add_points(one_level, 1, p),
                    Catch::Matchers::Contains("level 3 is not in the hierarchy"));
  CHECK_THROWS_AS(make("fixed", "{vertices: [1], nearest: [0, 0, 0]}"), InvalidConfig);
  CHECK_THROWS_AS(make("position", "{vertices: [1], offset: [1, 2]}"), InvalidConfig);
}
