// Every registered energy and constraint, on every back end it has, satisfies the contract
// its interface states — driven by the registries, so a new component is tested the day it is
// registered (a constraint without an example configuration here fails the suite).
#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>

#include <map>
#include <numeric>
#include <random>

#include "fairshape/experiment/components.h"
#include "fairshape/io/mesh_io.h"
#include "test_support.h"

using namespace fairshape;

namespace {

SparseMatrix hessian_of(const Energy& e, const SurfaceMesh& m, double weight) {
  Triplets t;
  e.add_hessian(m, weight, t);
  SparseMatrix H(m.n_vertices(), m.n_vertices());
  H.setFromTriplets(t.begin(), t.end());
  return H;
}

std::vector<Backend> backends_of(const std::string& name, const EnergyRegistry& r) {
  std::vector<Backend> out;
  for (Backend b : {Backend::Reference, Backend::Optimized})
    if (r.has(name, b)) out.push_back(b);
  return out;
}

// The same surface with its vertices renumbered by `perm` (new id k is old vertex perm[k]).
SurfaceMesh renumbered(const SurfaceMesh& m, const std::vector<int>& perm) {
  std::vector<int> new_id(perm.size());
  for (std::size_t k = 0; k < perm.size(); ++k) new_id[static_cast<std::size_t>(perm[k])] = static_cast<int>(k);
  MatrixX3 V(m.n_vertices(), 3);
  for (int k = 0; k < m.n_vertices(); ++k) V.row(k) = m.positions().row(perm[static_cast<std::size_t>(k)]);
  PolygonList F = m.polygons();
  for (auto& f : F)
    for (int& v : f) v = new_id[static_cast<std::size_t>(v)];
  return SurfaceMesh::from_polygons(V, F);
}

struct NamedMesh {
  std::string name;
  SurfaceMesh mesh;
};

std::vector<NamedMesh> test_meshes() {
  SurfaceMesh bumpy = test::grid(6);
  MatrixX3 V = bumpy.positions();
  for (int v = 0; v < V.rows(); ++v) V(v, 2) = 0.1 * std::sin(5 * V(v, 0)) * std::cos(4 * V(v, 1));
  return {{"closed quad torus", read_mesh(test::data_path("torus_quad.off"))},
          {"open bumpy quad grid", SurfaceMesh::from_polygons(V, bumpy.polygons())}};
}

double relative(const SparseMatrix& a, const SparseMatrix& b) { return (a - b).norm() / std::max(1e-300, b.norm()); }

// Every registered energy on every back end it has, with its default options.
template <class F>
void for_each_energy(F&& f) {
  const EnergyRegistry& reg = components().energies;
  REQUIRE(!reg.names().empty());
  for (const auto& name : reg.names())
    for (Backend b : backends_of(name, reg)) {
      INFO(name << " (" << to_string(b) << ")");
      Config defaults;
      f(*reg.create(name, b, defaults));
    }
}

}  // namespace

TEST_CASE("every energy: symmetric PSD Hessian, constants in its null space, linear in the weight, one assembly route",
          "[conformance][energy]") {
  for (const auto& mesh : test_meshes())
    for_each_energy([&](const Energy& e) {
        INFO("on the " << mesh.name);
        const SparseMatrix H = hessian_of(e, mesh.mesh, 1.0);
        REQUIRE(H.rows() == mesh.mesh.n_vertices());
        REQUIRE(H.norm() > 0);
        CHECK(Eigen::MatrixXd(H).allFinite());
        CHECK(relative(SparseMatrix(H.transpose()), H) <= 1e-12);
        // Every energy here measures shape through differences: a translation costs nothing.
        CHECK((H * Eigen::VectorXd::Ones(H.rows())).norm() <= 1e-10 * H.norm());
        const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig{Eigen::MatrixXd(H)};
        CHECK(eig.eigenvalues().minCoeff() >= -1e-10 * eig.eigenvalues().maxCoeff());
        CHECK(relative(hessian_of(e, mesh.mesh, 2.5), 2.5 * H) <= 1e-12);
        CHECK(relative(e.hessian(mesh.mesh, 1.0), H) <= 1e-12);
      });
}

TEST_CASE("every energy is independent of the vertex numbering", "[conformance][energy]") {
  for (const auto& mesh : test_meshes()) {
    std::vector<int> perm(static_cast<std::size_t>(mesh.mesh.n_vertices()));
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), std::mt19937(5));
    const SurfaceMesh shuffled = renumbered(mesh.mesh, perm);
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> P(mesh.mesh.n_vertices());
    for (std::size_t k = 0; k < perm.size(); ++k) P.indices()[static_cast<Eigen::Index>(perm[k])] = static_cast<int>(k);
    for_each_energy([&](const Energy& e) {
        INFO("on the " << mesh.name);
        const SparseMatrix H = hessian_of(e, mesh.mesh, 1.0);
        // P maps old ids to new ones: H_new = P H Pᵀ.
        const SparseMatrix expected = SparseMatrix(P * H * P.transpose());
        CHECK(relative(hessian_of(e, shuffled, 1.0), expected) <= 1e-10);
      });
  }
}

TEST_CASE("every energy's back ends agree", "[conformance][energy]") {
  const EnergyRegistry& reg = components().energies;
  for (const auto& mesh : test_meshes())
    for (const auto& name : reg.names()) {
      if (backends_of(name, reg).size() < 2) continue;
      INFO(name << " on the " << mesh.name);
      Config a, b;
      const SparseMatrix ref = hessian_of(*reg.create(name, Backend::Reference, a), mesh.mesh, 1.0);
      const SparseMatrix opt = hessian_of(*reg.create(name, Backend::Optimized, b), mesh.mesh, 1.0);
      CHECK(relative(opt, ref) <= 1e-12);
    }
}

TEST_CASE("every energy refuses an option it does not know", "[conformance][energy]") {
  const EnergyRegistry& reg = components().energies;
  for (const auto& name : reg.names()) {
    INFO(name);
    Config cfg(YAML::Load("{no_such_option: 1}"), "energy[0]");
    const Backend b = backends_of(name, reg).front();
    CHECK_THROWS_WITH((reg.create(name, b, cfg), cfg.check_no_unknown_keys()),
                      Catch::Matchers::Contains("energy[0].no_such_option"));
  }
}

namespace {

// One valid configuration per registered constraint, on the 5 × 5 grid of [0, 1]² (spacing
// 0.25). A constraint registered without an entry here fails the suite.
const std::map<std::string, std::string>& constraint_examples() {
  static const std::map<std::string, std::string> examples{
      {"fixed", "{region: {axis: x, from: 0.0, to: 0.3}}"},
      {"position", "{nearest: [0.5, 0.5, 0], offset: [0, 0, 0.2]}"},
      {"normal", "{nearest: [0.5, 0.5, 0], normal: [0, 1, 1]}"},
      {"rigid", "{boundary_loop_near: [0, 0, 0], rotation: {axis: [0, 0, 1], angle_deg: 30}, translation: [0, 0, 0.1]}"},
      {"curve", "{points: [[0, 0.55, 0], [1, 0.55, 0]], translation: [0, 0, 0.2]}"},
  };
  return examples;
}

DesignConstraints placed(const Constraint& c, const SurfaceMesh& m) {
  const LevelMeshes one_level = [&m](int) -> const SurfaceMesh& { return m; };
  DesignConstraints dc;
  c.add_to(one_level, 0, dc);
  return dc;
}

}  // namespace

TEST_CASE("every constraint: valid placements, finite targets, unit normals, deterministic, appended not replaced",
          "[conformance][constraint]") {
  const ConstraintRegistry& reg = components().constraints;
  const SurfaceMesh m = test::grid(4);
  for (const auto& name : reg.names())
    for (Backend b : {Backend::Reference, Backend::Optimized}) {
      if (!reg.has(name, b)) continue;
      INFO(name << " (" << to_string(b) << ")");
      REQUIRE(constraint_examples().count(name) == 1);  // add an example configuration above
      Config cfg(YAML::Load(constraint_examples().at(name)), "constraints[0]");
      const auto c = reg.create(name, b, cfg);
      cfg.check_no_unknown_keys();
      const DesignConstraints dc = placed(*c, m);
      CHECK(dc.points.size() + dc.normals.size() > 0);
      for (const auto& p : dc.points) {
        CHECK(p.level == 0);
        CHECK((p.vertex >= 0 && p.vertex < m.n_vertices()));
        CHECK(p.offset.allFinite());
        CHECK(!p.label.empty());
      }
      for (const auto& n : dc.normals) {
        CHECK((n.vertex >= 0 && n.vertex < m.n_vertices()));
        CHECK(std::abs(n.normal.norm() - 1) <= 1e-12);
        CHECK(!n.label.empty());
      }
      const DesignConstraints again = placed(*c, m);
      REQUIRE(again.points.size() == dc.points.size());
      for (std::size_t k = 0; k < dc.points.size(); ++k) {
        CHECK(again.points[k].vertex == dc.points[k].vertex);
        CHECK(again.points[k].offset == dc.points[k].offset);
      }
      // add_to appends: what was there stays.
      DesignConstraints both = dc;
      const LevelMeshes one_level = [&m](int) -> const SurfaceMesh& { return m; };
      c->add_to(one_level, 0, both);
      CHECK(both.points.size() == 2 * dc.points.size());
      CHECK(both.normals.size() == 2 * dc.normals.size());
    }
  for (const auto& [name, example] : constraint_examples()) CHECK(reg.has(name));  // no stale examples
}

TEST_CASE("every constraint names a level outside the hierarchy and an unknown option", "[conformance][constraint]") {
  const ConstraintRegistry& reg = components().constraints;
  const SurfaceMesh m = test::grid(4);
  const LevelMeshes one_level = [&m](int) -> const SurfaceMesh& { return m; };
  for (const auto& [name, example] : constraint_examples()) {
    INFO(name);
    YAML::Node at_level_3 = YAML::Load(example);
    at_level_3["level"] = 3;
    Config cfg(at_level_3, "constraints[0]");
    const auto c = reg.create(name, Backend::Reference, cfg);
    DesignConstraints dc;
    CHECK_THROWS_WITH(c->add_to(one_level, 0, dc), Catch::Matchers::Contains("level 3"));
    YAML::Node extra = YAML::Load(example);
    extra["no_such_option"] = 1;
    Config bad(extra, "constraints[0]");
    CHECK_THROWS_WITH((reg.create(name, Backend::Reference, bad), bad.check_no_unknown_keys()),
                      Catch::Matchers::Contains("constraints[0].no_such_option"));
  }
}
