// The second-order check without the dense eigen-solve (papers/sauvage/README.md, "Second-order
// checks cheaper than the solve"): inertia bisection on the banded KKT factor brackets the
// reduced Hessian's smallest eigenvalue that the dense check computes, at a minimum and at a
// saddle, in 3-D and in a planar problem's plane; its verdict and direction agree with the dense
// ones; and the run keys that choose the check refuse what they cannot do.
#include <catch2/catch.hpp>

#include <yaml-cpp/yaml.h>

#include "fairshape/core/config.h"
#include "fairshape/core/error.h"
#include "fairshape/curve_design/editing_loop.h"
#include "fairshape/curve_design/length_manifold.h"
#include "fairshape/curve_design/reduced_eigenvalue.h"
#include "fairshape/curve_design/second_order.h"
#include "fairshape/experiment/kinds/curve/curve_run.h"
#include "fairshape/experiment/run_outputs.h"
#include "fairshape/io/mesh_io.h"
#include "test_support.h"

using namespace fairshape;

namespace {

std::unique_ptr<LengthSolver> make_solver(const std::string& type, const std::string& yaml) {
  Config c(YAML::Load(yaml), "solver");
  auto s = curve_components().solvers.create(type, Backend::Optimized, c);
  c.check_no_unknown_keys();
  return s;
}

struct Wave {
  std::unique_ptr<CurveEnergy> bending;
  std::unique_ptr<CurveConstraintKind> lengths;
  CurveObjective objective;
  Polyline curve = read_polyline(test::source_path("data/curves/wave129.obj"));
  Wave() {
    Config none;
    bending = curve_components().energies.create("bending", Backend::Optimized, none);
    lengths = curve_components().constraints.create("segment_lengths", Backend::Optimized, none);
    objective.smoothness = bending.get();
    objective.beta = 0.01;
    objective.constraints = {lengths.get()};
  }
  // Figure 1's edit (the wave's end pulled along the chord), solved on the whole curve.
  PreparedCurveEdit prepare(double chord_scale, PlaneMode plane) const {
    CurveEdit e;
    e.options.solve_region = SolveRegion::Curve;
    e.options.plane = plane;
    CurveMove mv;
    mv.index = -1;
    mv.chord_scale = chord_scale;
    e.moves = {mv};
    return prepare_editing_loop(curve, 7, e, objective, Backend::Optimized);
  }
};

// The points the checks are compared at: a minimum (the trust region's answer at 95 %) and a
// saddle (the paper's loop, no escapes, at 70 %: README "Solvers" — it stops at one), each in
// the plane (keep) and in 3-D (free).
struct Case {
  std::string name;
  std::unique_ptr<LengthProblem> problem;
  MatrixX3 X;
};

std::vector<Case> cases() {
  const Wave w;
  std::vector<Case> out;
  for (PlaneMode plane : {PlaneMode::Keep, PlaneMode::Free}) {
    const std::string where = plane == PlaneMode::Keep ? " (in plane)" : " (3-D)";
    PreparedCurveEdit minimum = w.prepare(0.95, plane);
    const auto tr = make_solver("trust_region", "{length_tolerance: 1.0e-12, max_solves: 2000, second_order: dense}");
    MatrixX3 Xmin = tr->solve(*minimum.problem, minimum.stages.attracting).points;
    out.push_back({"minimum" + where, std::move(minimum.problem), Xmin});
    PreparedCurveEdit saddle = w.prepare(0.7, plane);
    const auto paper = make_solver("linearized", "{length_tolerance: 1.0e-12, max_solves: 5000, linearized: {saddle_escapes: 0}, second_order: off}");
    MatrixX3 Xs = paper->solve(*saddle.problem, saddle.stages.attracting).points;
    out.push_back({"saddle" + where, std::move(saddle.problem), Xs});
  }
  return out;
}

}  // namespace

TEST_CASE("inertia bisection brackets the dense smallest reduced-Hessian eigenvalue, at minima and saddles, in plane and in 3-D",
          "[sauvage][second_order]") {
  int saddles = 0, minima = 0;
  for (const Case& c : cases()) {
    INFO(c.name);
    const SecondOrderCheck dense = check_second_order(*c.problem, c.X);
    REQUIRE(dense.checked);
    const ReducedEigenvalueBracket b = smallest_reduced_eigenvalue(*c.problem, c.X);
    REQUIRE(b.ok);
    INFO("dense " << dense.min_eigenvalue << ", bracket [" << b.lower << ", " << b.upper << "], " << b.factorizations
                  << " factorizations");
    // The bracket holds the dense value (to the inertia's rounding, the floor) and is as narrow
    // as asked.
    const double slack = kReducedEigenvalueFloor * b.scale;
    CHECK(dense.min_eigenvalue >= b.lower - slack);
    CHECK(dense.min_eigenvalue <= b.upper + slack);
    CHECK(b.upper - b.lower <= std::max(kReducedEigenvalueTolerance * std::max(std::abs(b.lower), std::abs(b.upper)), slack) * 1.0000001);
    CHECK(b.scale >= dense.max_abs_eigenvalue);  // Gershgorin bounds the spectrum
    (dense.min_eigenvalue < 0 ? saddles : minima) += 1;
  }
  // Both kinds of point were really tested (in its plane the paper's loop ends at a minimum
  // here: the saddle's negative modes leave the plane).
  CHECK(saddles >= 1);
  CHECK(minima >= 1);
}

TEST_CASE("the inertia verdict is the dense one, and its direction is the dense eigenvector", "[sauvage][second_order]") {
  for (const Case& c : cases()) {
    INFO(c.name);
    const SecondOrderCheck dense = check_second_order(*c.problem, c.X);
    const SecondOrderCheck inertia = check_second_order_by_inertia(*c.problem, c.X, true);
    REQUIRE(inertia.checked);
    INFO(inertia.message);
    CHECK(inertia.is_minimum(kSecondOrderTolerance) == dense.is_minimum(kSecondOrderTolerance));
    CHECK(std::abs(inertia.min_eigenvalue - dense.min_eigenvalue) <= inertia.min_eigenvalue_error + kReducedEigenvalueFloor * inertia.max_abs_eigenvalue);
    CHECK(second_order_check(*c.problem, c.X, SecondOrderMode::Off, true).checked == false);
    if (dense.min_eigenvalue >= 0) {
      CHECK(inertia.direction.rows() == 0);  // asked only at negative curvature
      continue;
    }
    REQUIRE(inertia.direction.rows() == c.problem->n_points());
    const int n = 3 * c.problem->n_points();
    const Eigen::Map<const Eigen::VectorXd> d(inertia.direction.data(), n), e(dense.direction.data(), n);
    const SparseMatrix J = constraint_jacobian(c.problem->rows(c.X), c.problem->n_points());
    CHECK((J * d).norm() < 1e-8);  // tangent
    const SparseMatrix W = lagrangian_hessian(*c.problem, c.X, least_squares_multipliers(*c.problem, c.X));
    // A negative-curvature direction as deep as λ_min to the bracket's tolerance (the saddle has
    // a cluster of 14 negative eigenvalues, so the eigenvector itself is not pinned down: its
    // overlap with the dense one is only required to be large).
    const double rayleigh = d.dot(W * d);
    CHECK(rayleigh >= dense.min_eigenvalue - 1e-10 * std::abs(dense.min_eigenvalue));
    CHECK(rayleigh <= dense.min_eigenvalue + kReducedEigenvalueTolerance * std::abs(dense.min_eigenvalue));
    CHECK(std::abs(d.dot(e)) > 0.5);
  }
}

TEST_CASE("every solver reports the bracketed eigenvalue by default, none forms the dense reduced Hessian", "[sauvage][second_order]") {
  const Wave w;
  PreparedCurveEdit prepared = w.prepare(0.95, PlaneMode::Keep);
  for (const char* type : {"linearized", "trust_region"}) {
    INFO(type);
    const auto solver = make_solver(type, std::string("{length_tolerance: 1.0e-12, max_solves: 2000") +
                                              (type == std::string("linearized") ? ", linearized: {linearization: newton}}" : "}"));
    const LengthSolveReport r = solver->solve(*prepared.problem, prepared.stages.attracting);
    INFO(r.summary.message);
    REQUIRE(r.converged());
    const SecondOrderCheck dense = check_second_order(*prepared.problem, r.points);
    CHECK(r.min_reduced_hessian_eig == Approx(dense.min_eigenvalue).epsilon(2 * kReducedEigenvalueTolerance));
    CHECK(r.summary.message.find("inertia bisection") != std::string::npos);
  }
  const auto off = make_solver("linearized", "{length_tolerance: 1.0e-12, max_solves: 2000, second_order: off}");
  const LengthSolveReport r = off->solve(*prepared.problem, prepared.stages.attracting);
  CHECK(r.converged());
  CHECK(std::isnan(r.min_reduced_hessian_eig));
  CHECK(r.summary.message.find("second_order: off") != std::string::npos);
}

namespace {
YAML::Node wave_run(const std::string& solver, const std::string& output) {
  return YAML::Load(R"(
name: check
input: {curve: data/curves/wave129.obj}
edits: [{level: 0, moves: [{index: -1, chord_scale: 0.95}]}]
optimization:
  beta: 0.01
  solver: )" + solver + R"(
output: )" + output);
}
}  // namespace

TEST_CASE("second_order and wrinkle_scale keys: bad values are errors naming the key, dense refused above its limit",
          "[sauvage][second_order]") {
  const std::vector<std::string> dirs{test::source_path("")};
  CHECK_THROWS_WITH(CurveRunSpec::from_config(wave_run("{second_order: eigen}", "{vtk: none}"), dirs),
                    Catch::Contains("optimization.solver.second_order") && Catch::Contains("eigen") &&
                        Catch::Contains("inertia") && Catch::Contains("dense") && Catch::Contains("off"));
  CHECK_NOTHROW(CurveRunSpec::from_config(wave_run("{second_order: dense}", "{vtk: none}"), dirs));
  YAML::Node big = wave_run("{second_order: dense}", "{vtk: none}");
  big["input"]["resample"] = 1025;
  CHECK_THROWS_WITH(CurveRunSpec::from_config(big, dirs), Catch::Contains("optimization.solver.second_order") &&
                                                              Catch::Contains("600") && Catch::Contains("1025"));
  big["optimization"]["solver"]["second_order"] = "inertia";
  CHECK_NOTHROW(CurveRunSpec::from_config(big, dirs));
  CHECK_THROWS_WITH(CurveRunSpec::from_config(wave_run("{}", "{vtk: none, wrinkle_scale: sometimes}"), dirs),
                    Catch::Contains("output.wrinkle_scale"));
}

TEST_CASE("output.wrinkle_scale: false leaves the wrinkle columns empty, not zero", "[sauvage][second_order]") {
  for (bool on : {true, false}) {
    const auto dir = test::scratch_dir(on ? "wrinkle_scale_on" : "wrinkle_scale_off");
    create_run_folders(dir.string());
    CurveRunSpec spec = CurveRunSpec::from_config(
        wave_run("{type: linearized, second_order: off}", std::string("{vtk: none, final_curve: false, wrinkle_scale: ") +
                                                           (on ? "true" : "false") + "}"),
        {test::source_path("")});
    RunTables tables;
    const MetricRow row = execute_curve_run(spec, RunOutputs{dir.string(), "w", true, &tables});
    INFO(row.at("message"));
    CHECK(row.at("termination") == "converged");
    CHECK(row.at("min_reduced_hessian_eig") == "not_checked");
    for (const char* col : {"wrinkle_amplitude", "wrinkle_wavelength", "wrinkle_wavelength_segments"})
      CHECK(row.at(col).empty() == !on);
  }
}
