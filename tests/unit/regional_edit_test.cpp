// Boier-Martin et al. §4.2, region of influence: each constraint propagated to a level of its
// own and solved on its region there (design/influence.h, design/regional_edit.h).
#include <catch2/catch.hpp>

#include <cmath>

#include <Eigen/Geometry>

#include "fairshape/constraint/constraint_factories.h"
#include "fairshape/design/regional_edit.h"
#include "fairshape/design/rotation_aware_edit.h"
#include "fairshape/energy/local_rotations.h"
#include "fairshape/energy/energy.h"
#include "fairshape/experiment/components.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/problem/constrained_system.h"
#include "edit_test_support.h"
#include "test_support.h"

using namespace fairshape;

namespace {

using test::cholesky;

std::unique_ptr<Energy> detail_preserving() {
  Config cfg(YAML::Load("{alpha: 0.1, beta: 1.0}"), "energy");
  return components().energies.create("detail_preserving", Backend::Optimized, cfg);
}

// The cow subdivided `levels` times; its back third fixed, the nose moved.
struct CowEdit {
  explicit CowEdit(int levels)
      : h(read_mesh(test::data_path("cow.off")), SubdivisionOptions{}, levels, Backend::Optimized),
        energy(detail_preserving()),
        back(prescribed_offset(VertexSelection::slab(0, 0.0, 0.3), Vec3::Zero())),
        nose(prescribed_offset(VertexSelection::nearest({0.5, 0.0, 0.0}), {0.04, 0.06, 0.0})),
        top(prescribed_offset(VertexSelection::nearest({-0.05, 0.21, 0.0}), {0.0, 0.04, 0.0})) {}
  EditTerms terms(std::vector<const Constraint*> cs, std::vector<Influence> in) const {
    EditTerms t;
    t.energies = {{energy.get(), 1.0}};
    t.constraints = std::move(cs);
    t.influences = std::move(in);
    return t;
  }
  RegionalEditResult solve(const EditTerms& t, ConstraintMode mode = ConstraintMode::Kkt) const {
    const auto direct = cholesky();
    return solve_regional_edit(t, h, h.levels(), mode, *direct, Backend::Optimized, Config{});
  }
  Eigen::MatrixXd moved(const RegionalEditResult& r) const {
    return r.edited.mesh(h.levels()).positions() - h.mesh(h.levels()).positions();
  }
  MultiresSurface h;
  std::unique_ptr<Energy> energy;
  std::unique_ptr<Constraint> back, nose, top;
};

Influence held() {
  Influence i;
  i.held = true;
  return i;
}

Influence at(int level, int rings) {
  Influence i;
  i.level = level;
  i.rings = rings;
  return i;
}

double fraction_moved(const Eigen::MatrixXd& moved) {
  return (moved.rowwise().norm().array() > 1e-12).count() / static_cast<double>(moved.rows());
}

}  // namespace

TEST_CASE("region of influence: nothing outside a constraint's region moves, and the constraint is met",
          "[design][bm][influence]") {
  const CowEdit cow(2);
  for (int level : {0, 1, 2}) {
    const RegionalEditResult r = cow.solve(cow.terms({cow.back.get(), cow.nose.get()}, {held(), at(level, 1)}));
    INFO("influence level " << level);
    REQUIRE(r.summary.termination == Termination::Converged);
    const Eigen::MatrixXd moved = cow.moved(r);
    for (Eigen::Index v = 0; v < moved.rows(); ++v)
      if (r.region(v) == 0) REQUIRE(moved.row(v).norm() == 0.0);  // exactly: by construction
    CHECK(r.outside_region_move == 0.0);
    CHECK(r.constraint_violation < 1e-10);
    CHECK(moved.rowwise().norm().maxCoeff() > 0.03);  // the handle did move
  }
}

TEST_CASE("region of influence: a coarse level is global, a fine level local (Figure 1 b, c)",
          "[design][bm][influence]") {
  const CowEdit cow(2);
  const RegionalEditResult coarse = cow.solve(cow.terms({cow.back.get(), cow.nose.get()}, {held(), at(0, 2)}));
  const RegionalEditResult fine = cow.solve(cow.terms({cow.back.get(), cow.nose.get()}, {held(), at(2, 2)}));
  REQUIRE(coarse.passes.size() == 1);
  REQUIRE(fine.passes.size() == 1);
  // The same two rings cover 4^2 times more surface on the base than on level 2.
  CHECK(coarse.passes[0].surface_fraction > 8 * fine.passes[0].surface_fraction);
  CHECK(fraction_moved(cow.moved(coarse)) > 8 * fraction_moved(cow.moved(fine)));
  CHECK(fine.passes[0].surface_fraction < 0.01);
}

TEST_CASE("region of influence: one pass over the whole edit level is the plain single-level edit",
          "[design][bm][influence]") {
  const CowEdit cow(1);
  const EditTerms plain = cow.terms({cow.back.get(), cow.nose.get()}, {});
  DesignConstraints placed;
  const EditProblem p = assemble_edit_problem(plain, cow.h, 1, placed);
  const auto direct = cholesky();
  const EditSolution single = solve_edit(p, ConstraintMode::Kkt, *direct, Backend::Optimized);
  const RegionalEditResult r =
      cow.solve(cow.terms({cow.back.get(), cow.nose.get()}, {held(), at(1, Influence::kWholeLevel)}));
  const Eigen::MatrixXd delta = r.edited.mesh(1).positions() - cow.h.mesh(1).positions();
  CHECK(relative_error(delta, single.delta) < 1e-10);
}

TEST_CASE("region of influence: constraints of several levels combine, the finer pass keeps the coarser one",
          "[design][bm][influence]") {
  const CowEdit cow(2);
  const RegionalEditResult r = cow.solve(
      cow.terms({cow.back.get(), cow.top.get(), cow.nose.get()}, {held(), at(0, 2), at(2, 2)}));
  REQUIRE(r.summary.termination == Termination::Converged);
  REQUIRE(r.passes.size() == 2);
  CHECK(r.passes[0].level == 0);
  CHECK(r.passes[1].level == 2);
  CHECK(r.constraint_violation < 1e-10);  // the back handle, met on the base pass, is still met
  CHECK(r.outside_region_move == 0.0);
}

TEST_CASE("region of influence: the QP modes agree on a regional edit", "[design][bm][influence][qp]") {
  const CowEdit cow(1);
  const EditTerms t = cow.terms({cow.back.get(), cow.nose.get()}, {held(), at(0, 2)});
  const RegionalEditResult kkt = cow.solve(t, ConstraintMode::Kkt);
  const RegionalEditResult range = cow.solve(t, ConstraintMode::RangeSpace);
  REQUIRE(range.summary.termination == Termination::Converged);
  CHECK(relative_error(cow.moved(range), cow.moved(kkt)) < 1e-8);
}

TEST_CASE("region of influence: bad influence levels are errors naming the constraint", "[design][bm][influence]") {
  const CowEdit cow(2);
  const auto on_base = prescribed_offset(VertexSelection::nearest({0.5, 0.0, 0.0}), {0.0, 0.05, 0.0}, 0, false,
                                         "constraints[1]");
  const auto direct = cholesky();
  // Given on level 0, propagated to level 2: finer than where it is given.
  const EditTerms finer = cow.terms({cow.back.get(), on_base.get()}, {held(), at(2, 1)});
  CHECK_THROWS_WITH(check_regional_edit(finer, cow.h, 2, *direct, ConstraintMode::Kkt),
                    Catch::Contains("constraints[1]") && Catch::Contains("finer than level 0"));
  const EditTerms missing = cow.terms({cow.back.get(), cow.nose.get()}, {held(), at(5, 1)});
  CHECK_THROWS_WITH(check_regional_edit(missing, cow.h, 2, *direct, ConstraintMode::Kkt),
                    Catch::Contains("not in the hierarchy"));
}

// Beyond the paper: rotation-aware details (energy/local_rotations.h, design/rotation_aware_edit.h).
TEST_CASE("rotation-aware details: a rigid turn of both ends turns the whole model rigidly",
          "[design][bm][rotations]") {
  const MultiresSurface h(read_mesh(test::data_path("cow.off")), SubdivisionOptions{}, 1, Backend::Optimized);
  const SurfaceMesh& rest = h.mesh(1);
  const auto energy = detail_preserving();
  // Both ends of the cow, held to one rigid motion: 60 degrees about z through the origin.
  const Eigen::Vector3d lo = rest.positions().colwise().minCoeff(), hi = rest.positions().colwise().maxCoeff();
  YAML::Node n = YAML::Load("{type: rigid, rotation: {axis: [0, 0, 1], angle_deg: 60, center: [0, 0, 0]}}");
  for (int v = 0; v < rest.n_vertices(); ++v) {
    const double x = (rest.position(v).x() - lo.x()) / (hi.x() - lo.x());
    if (x < 0.15 || x > 0.85) n["vertices"].push_back(v);
  }
  Config cfg(n, "constraints[0]");
  const auto ends = components().constraints.create("rigid", Backend::Optimized, cfg);
  EditTerms terms;
  terms.energies = {{energy.get(), 1.0}};
  terms.constraints = {ends.get()};
  DesignConstraints placed;
  const EditProblem p = assemble_edit_problem(terms, h, 1, placed);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(M_PI / 3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::MatrixXd rigid = rest.positions() * R.transpose() - rest.positions();
  const double size = (hi - lo).norm();
  const auto direct = cholesky();

  const RotationAwareSolution linear =
      solve_rotation_aware(p, terms.energies, rest, ConstraintMode::Kkt, *direct, Backend::Optimized, Config{}, {0, 1e-4});
  RotationAwareOptions o;
  o.iterations = 200;
  o.tolerance = 1e-8;
  const RotationAwareSolution turned =
      solve_rotation_aware(p, terms.energies, rest, ConstraintMode::Kkt, *direct, Backend::Optimized, Config{}, o);
  INFO("rounds " << turned.rounds << ", last change " << turned.last_change);
  REQUIRE(turned.solution.summary.termination == Termination::Converged);
  const double linear_off = (linear.solution.delta - rigid).rowwise().norm().maxCoeff() / size;
  const double turned_off = (turned.solution.delta - rigid).rowwise().norm().maxCoeff() / size;
  INFO("linear " << linear_off << ", rotation-aware " << turned_off << " after " << turned.rounds << " rounds");
  CHECK(linear_off > 1e-2);  // the linear energy shears the middle of the cow
  // The rigid motion costs nothing once the details may turn. E_R is flat along the turn
  // (measured: E_R 1e-3 of the linear answer's 7e5 leaves the cow 7e-6 of its size off).
  CHECK(turned_off < 2e-5);
  CHECK(turned.rounds < 150);
  const auto turning = energy->local_rotations(rest, 1.0);
  const MatrixX3 at_linear = rest.positions() + MatrixX3(linear.solution.delta);
  const MatrixX3 at_turned = rest.positions() + MatrixX3(turned.solution.delta);
  CHECK(turning->energy(at_turned) < 1e-7 * turning->energy(at_linear));
  // The rounds' objective is E_R (the global step's quadratic completed by its constant) ...
  CHECK(turned.energy == Approx(turning->energy(at_turned)).epsilon(1e-6).margin(1e-9 * turning->energy(at_linear)));
  // ... and no round raises it (up to the solves' rounding): the safeguard keeps a descent.
  for (std::size_t k = 1; k < turned.energy_history.size(); ++k)
    CHECK(turned.energy_history[k] <= turned.energy_history[k - 1] + 1e-9 * turned.energy_history.front());

  o.iterations = 1;  // too few rounds for the tolerance: said, not reported as converged
  const RotationAwareSolution short_of =
      solve_rotation_aware(p, terms.energies, rest, ConstraintMode::Kkt, *direct, Backend::Optimized, Config{}, o);
  CHECK(short_of.solution.summary.termination == Termination::MaxIterations);
  CHECK_THAT(short_of.solution.summary.message, Catch::Contains("above the tolerance"));
}
