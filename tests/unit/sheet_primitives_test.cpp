// The constraint primitives of Welch & Witkin §4.2 beyond points, tangents, normals and curves:
// offset relations between two points (§4.2.1), ribbons (a curve's position and the slope
// across it, §5) and sub-regions (§4.2.2). Each solved by the sheet solvers is compared with a
// dense reference built here from the basis alone: the same energy, the constraints imposed
// pointwise (collocation dense enough to be equivalent when the target lies in the surface's
// space), minimized on the null space of the collocation rows.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <yaml-cpp/yaml.h>

#include "fairshape/bspline/region_constraint.h"
#include "fairshape/bspline/ribbon_constraint.h"
#include "fairshape/bspline/sheet_file.h"
#include "fairshape/bspline/sheet_geometry.h"
#include "fairshape/bspline/variational_sheet.h"
#include "fairshape/core/config.h"
#include "fairshape/experiment/config_loader.h"
#include "fairshape/qp/qp_solver.h"
#include "sheet_test_support.h"

using namespace fairshape;
using namespace fairshape::bspline;
using Catch::Matchers::Contains;

namespace {

// The flat 8 × 8 sheet (test::flat_sheet), thin plate with slight tension.
struct Fixture {
  SheetEnergy energy;
  VariationalSheet sheet = test::flat_sheet();
  SheetShape shape = sheet.surface().shape();
  Fixture() { energy.weights.alpha = 0.01 * Eigen::Matrix2d::Identity(); }
  std::vector<SheetConstraint> pins() const { return test::corner_pins(sheet); }
};

// Collocation rows built from the basis (value or a design-unit derivative combination).
struct DenseRows {
  std::vector<Eigen::RowVectorXd> rows;
  std::vector<Eigen::RowVector3d> targets;
  void add(const HierarchicalSurface& s, double u, double v, double value, double du, double dv, const Vec3& target) {
    BasisRow b;
    s.basis(u, v, b);
    Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(s.dof_count());
    for (const BasisEntry& e : b) r[e.dof] += value * e.value + du * e.du + dv * e.dv;
    rows.push_back(r);
    targets.push_back(target.transpose());
  }
};

// argmin ½ tr(PᵀHP) subject to A P = C, on the null space of A (dependent rows allowed when
// consistent). Returns P (dofs × 3).
Eigen::MatrixXd dense_minimizer(const SparseMatrix& H_sparse, const DenseRows& d) {
  const Eigen::MatrixXd H(H_sparse);
  Eigen::MatrixXd A(static_cast<Eigen::Index>(d.rows.size()), H.rows()), C(A.rows(), 3);
  for (Eigen::Index i = 0; i < A.rows(); ++i) A.row(i) = d.rows[static_cast<std::size_t>(i)], C.row(i) = d.targets[static_cast<std::size_t>(i)];
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(A);
  cod.setThreshold(1e-10);
  const Eigen::MatrixXd P0 = cod.solve(C);
  REQUIRE((A * P0 - C).norm() <= 1e-9 * (1 + C.norm()));  // consistent
  Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  lu.setThreshold(1e-10);
  const Eigen::MatrixXd Z = lu.kernel();
  const Eigen::MatrixXd reduced = Z.transpose() * H * Z;
  return P0 - Z * reduced.ldlt().solve(Z.transpose() * (H * P0));
}

double energy_of(const SparseMatrix& H, const Eigen::MatrixXd& P) { return 0.5 * (P.transpose() * (H * P)).trace(); }

// Solves with every solver and compares with the dense reference. `locked`: a design the
// constraint policy calls ill_conditioned (a region's rows determine control points whose
// functions barely reach it: README, "Offsets, ribbons and regions") — the answer must still be
// the minimizer: KKT's to 1e-7, the others' to 1e-4, unless QR-penalty reports that its answer
// still moves.
void check_against(const Fixture& f, const std::vector<SheetConstraint>& constraints, const DenseRows& reference,
                   bool locked = false) {
  const SparseMatrix H = thin_plate_hessian(f.sheet.surface(), f.energy.weights, Backend::Reference);
  const Eigen::MatrixXd expected = dense_minimizer(H, reference);
  const double expected_energy = energy_of(H, expected);
  REQUIRE(expected_energy > 1e-6);  // the constraints bend the sheet
  for (const std::string solver : {"kkt", "range_space", "qr_penalty"}) {
    INFO(solver);
    VariationalSheet sheet = f.sheet;
    Config cfg(YAML::Load("{}"), "solver");
    auto qp = qp::qp_solver_registry().create(solver, Backend::Optimized, cfg);
    const DesignReport r = solve_sheet(sheet, f.energy, constraints, *qp, {}, Backend::Optimized);
    const Termination t = r.qp.summary.termination;
    INFO(r.message);
    REQUIRE((t == Termination::Converged || (locked && t == Termination::IllConditioned)));
    // QR-penalty says when its answer still moves between penalty steps (the region's weak
    // directions): not an answer to compare.
    if (solver == "qr_penalty" && t == Termination::IllConditioned && r.message.find("still moved") != std::string::npos) continue;
    const double tolerance = locked && solver != "kkt" ? 1e-4 : 1e-7;
    CHECK(std::abs(r.energy - expected_energy) <= tolerance * expected_energy);
    CHECK((sheet.coefficients() - expected).cwiseAbs().maxCoeff() <= 10 * tolerance);
  }
}

}  // namespace

TEST_CASE("offset relation between two points (§4.2.1): the dense solve with w(a) − w(b) = d", "[sheet][primitives]") {
  Fixture f;
  std::vector<SheetConstraint> cs = f.pins();
  SheetConstraint offset;
  offset.kind = SheetConstraint::Kind::Offset;
  offset.u = 6, offset.v = 4, offset.other = {2, 4};
  offset.target = Vec3(1.0, 0.2, 0.4);  // initially (1, 0, 0): the pair is tilted and sheared
  cs.push_back(offset);
  const HierarchicalSurface& s = f.sheet.surface();
  DenseRows d;
  for (const SheetConstraint& c : f.pins()) d.add(s, c.u, c.v, 1, 0, 0, c.target);
  {
    BasisRow a, b;
    s.basis(6, 4, a);
    s.basis(2, 4, b);
    Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(s.dof_count());
    for (const BasisEntry& e : a) r[e.dof] += e.value;
    for (const BasisEntry& e : b) r[e.dof] -= e.value;
    d.rows.push_back(r);
    d.targets.push_back(offset.target.transpose());
  }
  check_against(f, cs, d);
  // The rows themselves: one row, met by the solve to rounding.
  const ConstraintRows rows = offset_rows(s, {6, 4}, {2, 4}, offset.target);
  CHECK(rows.A.rows() == 1);
  CHECK_THROWS_WITH(offset_rows(s, {2, 4}, {2, 4}, offset.target), Contains("are the same"));
  CHECK_THROWS_WITH(offset_rows(s, {9, 4}, {2, 4}, offset.target), Contains("outside the parameter domain"));
}

TEST_CASE("ribbon (§5): a lifted curve whose cross slope is held matches the dense solve, and the plain curve does not",
          "[sheet][primitives]") {
  Fixture f;
  const HierarchicalSurface& s = f.sheet.surface();
  // Along v = 3 (off the middle, so that a plain curve tilts the sheet across it) from u = 2 to
  // 6, lifted 0.3; the slope across it (to the left of +u: +v) kept flat, as on the initial
  // sheet: (0, 1, 0) per design length.
  SheetConstraint ribbon;
  ribbon.kind = SheetConstraint::Kind::Curve;
  ribbon.curve.uv = {{2, 3}, {6, 3}};
  ribbon.curve.space = {Vec3(0.5, 0.75, 0.3), Vec3(1.5, 0.75, 0.3)};
  ribbon.ribbon = true;
  ribbon.cross = Vec3(0, 1, 0);
  std::vector<SheetConstraint> cs = f.pins();
  cs.push_back(ribbon);
  DenseRows d;
  for (const SheetConstraint& c : f.pins()) d.add(s, c.u, c.v, 1, 0, 0, c.target);
  for (int k = 0; k <= 16; ++k) {  // 4 points per span, more than the 7 functions of the trace
    const double u = 2 + 4.0 * k / 16;
    d.add(s, u, 3, 1, 0, 0, Vec3(0.25 * u, 0.75, 0.3));
    d.add(s, u, 3, 0, 0, 1 / f.shape.span_size.y(), Vec3(0, 1, 0));
  }
  check_against(f, cs, d);

  Config none;
  auto kkt = qp::qp_solver_registry().create("kkt", Backend::Optimized, none);
  // The cross slope taken from the initial sheet is the same constraint here.
  SheetConstraint traced = ribbon;
  traced.surface = std::make_shared<const SurfaceTrace>(SurfaceTrace{s, f.sheet.coefficients()});
  traced.cross = Vec3(5, 5, 5);  // ignored when a surface is given
  VariationalSheet a = f.sheet, b = f.sheet, plain = f.sheet;
  std::vector<SheetConstraint> with_traced = f.pins();
  with_traced.push_back(traced);
  const DesignReport ra = solve_sheet(a, f.energy, cs, *kkt, {}, Backend::Optimized);
  const DesignReport rb = solve_sheet(b, f.energy, with_traced, *kkt, {}, Backend::Optimized);
  CHECK(std::abs(ra.energy - rb.energy) <= 1e-9 * ra.energy);
  for (double t : {0.0, 0.3, 0.5, 0.9})
    CHECK((cross_tangent_at(a.surface(), a.coefficients(), ribbon.curve.uv, t) - Vec3(0, 1, 0)).norm() < 1e-9);
  // Without the ribbon the lifted curve tilts the sheet across it (a ridge), at lower energy.
  std::vector<SheetConstraint> curve_only = cs;
  curve_only.back().ribbon = false;
  const DesignReport rp = solve_sheet(plain, f.energy, curve_only, *kkt, {}, Backend::Optimized);
  CHECK(rp.energy < ra.energy);
  CHECK(std::abs(cross_tangent_at(plain.surface(), plain.coefficients(), ribbon.curve.uv, 0.5).z()) > 0.01);
}

TEST_CASE("region (§4.2.2): a lifted rectangle matches the dense solve, also on a refined sheet with dependent rows",
          "[sheet][primitives]") {
  for (const bool refined : {false, true}) {
    INFO((refined ? "refined around the region" : "unrefined"));
    Fixture f;
    if (refined) f.sheet.refine({{0, 3, 3}, {0, 4, 3}, {0, 3, 4}, {0, 4, 4}, {0, 2, 2}});
    const HierarchicalSurface& s = f.sheet.surface();
    SheetConstraint region;
    region.kind = SheetConstraint::Kind::Region;
    region.u = 3, region.v = 3, region.other = {5, 5};
    region.surface = std::make_shared<const SurfaceTrace>(SurfaceTrace{s, f.sheet.coefficients()});
    region.target = Vec3(0, 0, 0.2);
    std::vector<SheetConstraint> cs = f.pins();
    cs.push_back(region);
    DenseRows d;
    for (const SheetConstraint& c : f.pins()) d.add(s, c.u, c.v, 1, 0, 0, c.target);
    const int n = refined ? 16 : 8;  // collocation: 4 points per finest cell and direction
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) {
        const double u = 3 + 2.0 * i / n, v = 3 + 2.0 * j / n;
        d.add(s, u, v, 1, 0, 0, s.position(f.sheet.coefficients(), u, v) + region.target);
      }
    check_against(f, cs, d, /*locked=*/true);
    const ConstraintRows rows = region_rows(s, {3, 5}, {5, 5.5}, *region.surface, Vec3::Zero());
    CHECK(rows.A.rows() > 0);
    CHECK_THROWS_WITH(region_rows(s, {3, 5}, {3, 6}, *region.surface, Vec3::Zero()), Contains("empty"));
  }
}

TEST_CASE("offset, ribbon and region keys in a sheet config: the example runs, bad keys name the valid ones", "[sheet][primitives]") {
  YAML::Node cfg = load_experiment_config(test::source_path("configs/welch-witkin/primitives.yaml"), {});
  cfg["output"]["vtk"] = "none";
  MetricRow row;
  const auto steps = test::run_sheet_steps(cfg, "sheet_primitives_example", "example", row);
  INFO(row.at("message"));
  CHECK(row.at("termination") == "converged");
  REQUIRE(steps.size() == 3);
  CHECK(std::stod(steps[0][7]) < 1e-9);  // the straight ribbon is met exactly (its targets are in the trace space)

  const auto refused = [&](const std::string& path, const std::string& value) {
    YAML::Node bad = YAML::Clone(cfg);
    set_by_path(bad, path, YAML::Load(value));
    return SheetRunSpec::from_config(bad);
  };
  CHECK_THROWS_WITH(refused("constraints.0.type", "ribon"), Contains("ribbon") && Contains("offset") && Contains("region"));
  CHECK_THROWS_WITH(refused("constraints.4.offset", "later"), Contains("initial"));
  CHECK_THROWS_WITH(refused("constraints.5.cross_tangent", "flat"), Contains("initial") && Contains("current"));
  CHECK_THROWS_WITH(refused("constraints.6.surface", "rest"), Contains("initial") && Contains("current"));
  CHECK_THROWS_WITH(refused("constraints.6.corners", "[[1, 1]]"), Contains("[[u0, v0], [u1, v1]]"));
  CHECK_THROWS_WITH(refused("constraints.6.corners", "[[1, 1], [1, 2]]"), Contains("empty"));
  CHECK_THROWS_WITH(refused("constraints.6.corners", "[[1, 1], [3, 2]]"), Contains("constraints[6].corners[1]"));
  CHECK_THROWS_WITH(refused("constraints.6.shift", "[0, 0, 1]"), Contains("shift"));
  CHECK_THROWS_WITH(refused("constraints.4.from", "[0.5]"), Contains("[u, v]"));
}

TEST_CASE("offset: initial, ribbon cross_tangent: current and region surface: initial take the surfaces they name",
          "[sheet][primitives]") {
  // Step 0 lifts the middle; step 1 adds an offset pair at its initial offset, a ribbon along
  // v = 1.25 keeping the slope the step-0 sheet has there, and a region holding the initial
  // (flat) sheet in a corner, while the middle is lifted further. 16 × 16 spans: each away from
  // the others' reach (a region determines every control point reaching it, r spans around).
  const std::string cfg = std::string(R"(
name: held
sheets: [{name: s, spans: [16, 16], size: [2, 2]}]
energy: {alpha: 0.01, beta: 1}
curves:
  - {name: line, from_surface: {sheet: s, uv: [[0.75, 1.25], [1.5, 1.25]], surface: current}, samples: 9}
output: {vtk: all}
constraints:)") + test::kCornerPinsYaml + R"(
  - {type: point, uv: [1, 1], by: [0, 0, 0.3], moves: [{step: 1, by: [0, 0, 0.2]}]}
  - {type: offset, uv: [1.5, 0.5], from: [1.0, 0.75], offset: initial, step: 1}
  - {type: ribbon, curve: line, cross_tangent: current, step: 1}
  - {type: region, corners: [[0, 1.5], [0.25, 1.75]], surface: initial, step: 1}
)";
  const auto dir = test::scratch_dir("sheet_primitives_held");
  create_run_folders(dir.string());
  SheetRunSpec spec = SheetRunSpec::from_config(YAML::Load(cfg));
  const MetricRow row = execute_sheet_run(spec, RunOutputs{dir.string(), "held", true, nullptr});
  INFO(row.at("message"));
  REQUIRE(row.at("termination") == "converged");
  const VariationalSheet step0 = load_sheet((dir / "sheets" / "held_step0_s.sheet").string());
  const VariationalSheet last = load_sheet((dir / "sheets" / "held_s.sheet").string());
  const auto at = [](const VariationalSheet& s, double u, double v) {  // design units: 8 spans per unit
    return Vec3(s.surface().position(s.coefficients(), 8 * u, 8 * v));
  };
  // The offset pair keeps the initial sheet's offset (0.5, −0.25, 0), though step 0 bent the sheet.
  const Vec3 initial_offset(0.5, -0.25, 0);
  CHECK((at(last, 1.5, 0.5) - at(last, 1.0, 0.75) - initial_offset).norm() < 1e-9);
  CHECK((at(step0, 1.5, 0.5) - at(step0, 1.0, 0.75) - initial_offset).norm() > 1e-2);
  // The ribbon keeps step 0's slope across its line (to its left: +v), not the flat sheet's.
  const std::vector<Eigen::Vector2d> line{{6, 10}, {12, 10}};
  for (double t : {0.25, 0.5, 0.75}) {
    const Vec3 before = cross_tangent_at(step0.surface(), step0.coefficients(), line, t);
    CHECK((cross_tangent_at(last.surface(), last.coefficients(), line, t) - before).norm() < 1e-8);
    CHECK((before - Vec3(0, 1, 0)).norm() > 1e-3);
  }
  // The region is the flat initial sheet again.
  for (double u : {0.0, 0.1, 0.25})
    for (double v : {1.5, 1.7})
      CHECK(std::abs(at(last, u, v).z()) < 1e-9);
}
