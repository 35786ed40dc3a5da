// Sauvage, Hahmann and Bonneau's length-preserving curve editing: energies, constraints, the
// linearized loop (both back ends), the Ceres solve, the explicit step and the editing loop.
#include <catch2/catch.hpp>

#include <random>

#include "core/config.h"
#include "curve_design/curve_metrics.h"
#include "curve_design/editing_loop.h"
#include "curve_design/kkt_factor.h"
#include "curves/multires_polyline.h"
#include "io/mesh_io.h"

using namespace fairshape;

namespace {

Polyline bundled(const std::string& name) { return read_polyline(std::string(FAIRSHAPE_SOURCE_DIR) + "/data/curves/" + name); }

std::unique_ptr<LengthSolver> make_solver(const std::string& type, Backend b, const std::string& yaml = "{}") {
  Config c(YAML::Load(yaml), "solver");
  auto s = curve_components().solvers.create(type, b, c);
  c.check_no_unknown_keys();
  return s;
}

struct Recipe {
  std::unique_ptr<CurveEnergy> bending;
  std::vector<std::unique_ptr<CurveConstraintKind>> kinds;
  CurveObjective objective;
  explicit Recipe(double beta, bool pin_edited = false) {
    Config none;
    bending = curve_components().energies.create("bending", Backend::Reference, none);
    kinds.push_back(curve_components().constraints.create("segment_lengths", Backend::Reference, none));
    if (pin_edited) kinds.push_back(curve_components().constraints.create("pin", Backend::Reference, none));
    objective.smoothness = bending.get();
    objective.beta = beta;
    for (const auto& k : kinds) objective.constraints.push_back(k.get());
  }
};

// The Figure 1 edit: the wave's right end pulled to 70% of the chord, at the coarsest level.
CurveEdit compress(double scale, int e = 0, int w = -1) {
  CurveEdit edit;
  edit.edit_level = e;
  edit.wrinkle_level = w;
  CurveMove mv;
  mv.index = -1;
  mv.chord_scale = scale;
  edit.moves.push_back(mv);
  return edit;
}

double scale_of(const MatrixX3& X) { return (X.colwise().maxCoeff() - X.colwise().minCoeff()).norm(); }

}  // namespace

TEST_CASE("curve bending: the paper's banded H, symmetric, blind to affine curves", "[sauvage]") {
  const SparseMatrix H = stencil_hessian(bending_stencils(7, false), 7);
  const Eigen::MatrixXd D = Eigen::MatrixXd(H) * 8;
  CHECK(D.row(0).head(3) == Eigen::RowVector3d(1, -2, 1));
  CHECK(D.row(1).head(4) == Eigen::RowVector4d(-2, 5, -4, 1));
  CHECK(D.row(3) == (Eigen::RowVectorXd(7) << 0, 1, -4, 6, -4, 1, 0).finished());
  CHECK((D - D.transpose()).norm() == 0);
  const Eigen::VectorXd affine = Eigen::VectorXd::LinSpaced(7, 0.5, 3.5);
  CHECK((H * affine).norm() < 1e-14);
  // ½ XᵀHX is the stencil sum.
  MatrixX3 X = MatrixX3::Random(7, 3);
  const double quad = 0.5 * (X.transpose() * H * X).trace();
  CHECK(quad == Approx(stencil_energy(bending_stencils(7, false), X, X)).epsilon(1e-13));
}

TEST_CASE("curve constraints: gradients match finite differences", "[sauvage]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  MatrixX3 X(6, 3);
  for (int i = 0; i < X.size(); ++i) X.data()[i] = u(rng);
  const SegmentLengths lengths(Eigen::VectorXd::Constant(6, 0.7), true);
  const PinnedPoints pins({2, 4}, MatrixX3::Zero(2, 3));
  for (const CurveConstraint* c : {static_cast<const CurveConstraint*>(&lengths), static_cast<const CurveConstraint*>(&pins)})
    for (int r = 0; r < c->rows(); ++r) {
      const ConstraintRow row = c->evaluate(r, X);
      for (int k = 0; k < row.size; ++k)
        for (int d = 0; d < 3; ++d) {
          MatrixX3 Xp = X, Xm = X;
          Xp(row.points[k], d) += 1e-6;
          Xm(row.points[k], d) -= 1e-6;
          const double fd = (c->evaluate(r, Xp).value - c->evaluate(r, Xm).value) / 2e-6;
          CHECK(row.gradient[k][d] == Approx(fd).margin(1e-8));
        }
    }
}

TEST_CASE("linearized loop: lengths to 1e-10 at a constrained stationary point, both back ends agree", "[sauvage]") {
  const Polyline wave = bundled("wave129.obj");
  const Recipe recipe(0.01);
  EditStages stages[2];
  int i = 0;
  for (Backend b : {Backend::Reference, Backend::Optimized}) {
    const auto solver = make_solver("linearized", b, "{length_tolerance: 1e-12, stationarity_tolerance: 1e-9}");
    stages[i] = run_editing_loop(wave, 7, compress(0.8, 0, 4), recipe.objective, *solver, b);
    const EditStages& s = stages[i++];
    INFO(s.solve.summary.message);
    REQUIRE(s.solve.converged());
    const CurveMetrics m = measure_curve(s.final, false, segment_lengths(wave.points, false), s.attracting);
    CHECK(m.length_error_max <= 1e-10);
    CHECK(std::abs(m.total_length_change) <= 1e-10);
    CHECK(m.wrinkles > 0);  // compressing by 20% must buckle the curve
  }
  CHECK((stages[0].final - stages[1].final).cwiseAbs().maxCoeff() <= 1e-9 * scale_of(wave.points));
  CHECK(stages[0].solve.solves == stages[1].solve.solves);

  // Stationarity checked independently: least-squares multipliers for the final curve.
  std::vector<std::unique_ptr<CurveConstraint>> cons;
  cons.push_back(std::make_unique<SegmentLengths>(segment_lengths(wave.points, false), false));
  const LengthProblem p(stages[1].attracting, false, paper_objective(recipe.objective, 129, false), std::move(cons));
  CHECK(p.stationarity(stages[1].final) <= 1e-8);
  CHECK(p.stationarity(stages[1].attracting) > 1e-3);  // the check can fail
}

TEST_CASE("linearized loop: beta = 1 and an attractor already of the right lengths comes back unchanged", "[sauvage]") {
  const Polyline ring = bundled("ring128.obj");  // closed, in 3D
  const Recipe recipe(1.0);
  for (Backend b : {Backend::Reference, Backend::Optimized}) {
    const auto solver = make_solver("linearized", b);
    const EditStages s = run_editing_loop(ring, 5, CurveEdit{}, recipe.objective, *solver, b);
    REQUIRE(s.solve.converged());
    CHECK(s.solve.solves == 1);
    CHECK((s.final - ring.points).cwiseAbs().maxCoeff() <= 1e-13);
  }
}

TEST_CASE("editing loop without moves reproduces the reference at every stage", "[sauvage]") {
  const Polyline helix = bundled("helix257.obj");
  const Recipe recipe(0.1);
  const auto solver = make_solver("linearized", Backend::Optimized);
  CurveEdit edit;
  edit.edit_level = 2;
  edit.wrinkle_level = 4;
  const EditStages s = run_editing_loop(helix, 8, edit, recipe.objective, *solver, Backend::Optimized);
  CHECK((s.edited - helix.points).cwiseAbs().maxCoeff() <= 1e-14);
  CHECK((s.attracting - helix.points).cwiseAbs().maxCoeff() <= 1e-12);
  CHECK(s.explicit_step.moved_midpoints == 0);
  REQUIRE(s.solve.converged());  // β < 1: the result is smoother than the helix, of its lengths
  CHECK(measure_curve(s.final, false, segment_lengths(helix.points, false), s.attracting).length_error_max <= 1e-12);
}

TEST_CASE("explicit step: level w+1 edges get the reference lengths, compressing and stretching", "[sauvage]") {
  const Polyline wave = bundled("wave129.obj");
  for (double scale : {0.6, 1.02}) {
    for (Backend b : {Backend::Reference, Backend::Optimized}) {
      const int w = 3;
      // The loop's way: move the coarsest polygon's end, then reconstruct to level w.
      const PolylineHierarchy h = decompose(wave, 7, b);
      MatrixX3 cw = h.coarse;
      cw.row(1) = cw.row(0) + scale * (cw.row(1) - cw.row(0));
      const Eigen::RowVector3d moved_end = cw.row(1);
      for (int j = 0; j < w; ++j) cw = synthesis_step(cw, h.details[j], false, b);
      MatrixX3 dw = h.details[w];
      const Eigen::VectorXd target = segment_lengths(reconstruct(h, w + 1, b).points, false);
      const ExplicitLengthReport rep = preserve_lengths_explicitly(cw, dw, target, false, static_cast<int>(cw.rows()) - 1, b);
      const MatrixX3 fine = synthesis_step(cw, dw, false, b);
      const Eigen::VectorXd got = segment_lengths(fine, false);
      CHECK((got - target).cwiseAbs().maxCoeff() <= 1e-12);
      CHECK(rep.moved_midpoints > 0);
      if (scale > 1) CHECK(rep.shortened_segments > 0);
      else CHECK(rep.shortened_segments == 0);
      CHECK((cw.row(cw.rows() - 1) - moved_end).norm() == 0);  // the anchor (the moved point) stays
    }
  }
}

TEST_CASE("the explicit step brings the attracting curve near the lengths and cuts the solves", "[sauvage]") {
  const Polyline wave = bundled("wave129.obj");
  const Recipe recipe(0.01);
  const auto solver = make_solver("linearized", Backend::Optimized, "{stationarity_tolerance: 0, max_solves: 5000}");
  const EditStages plain = run_editing_loop(wave, 7, compress(0.7, 0, -1), recipe.objective, *solver, Backend::Optimized);
  const EditStages two_step = run_editing_loop(wave, 7, compress(0.7, 0, 4), recipe.objective, *solver, Backend::Optimized);
  REQUIRE(plain.solve.converged());
  REQUIRE(two_step.solve.converged());
  const Eigen::VectorXd l = segment_lengths(wave.points, false);
  const auto before = [&](const MatrixX3& X) { return measure_curve(X, false, l, X).length_error_max; };
  CHECK(before(two_step.attracting) < before(plain.attracting));
  CHECK(two_step.solve.solves < plain.solve.solves);
}

TEST_CASE("newton linearization and MINRES reach the same curve as the paper's direct loop", "[sauvage]") {
  const Polyline wave = bundled("wave129.obj");
  const Recipe recipe(0.05);
  const auto paper = make_solver("linearized", Backend::Optimized, "{length_tolerance: 1e-12}");
  const auto newton = make_solver("linearized", Backend::Optimized, "{length_tolerance: 1e-12, linearized: {linearization: newton}}");
  const auto minres = make_solver("linearized", Backend::Reference, "{linearized: {kkt: minres}, length_tolerance: 1e-10, stationarity_tolerance: 1e-7}");
  const EditStages a = run_editing_loop(wave, 7, compress(0.85, 0, 3), recipe.objective, *paper, Backend::Optimized);
  const EditStages b = run_editing_loop(wave, 7, compress(0.85, 0, 3), recipe.objective, *newton, Backend::Optimized);
  const EditStages c = run_editing_loop(wave, 7, compress(0.85, 0, 3), recipe.objective, *minres, Backend::Reference);
  REQUIRE(a.solve.converged());
  REQUIRE(b.solve.converged());
  REQUIRE(c.solve.converged());
  CHECK(b.solve.solves <= a.solve.solves);
  CHECK((a.final - b.final).cwiseAbs().maxCoeff() <= 1e-8);
  CHECK((a.final - c.final).cwiseAbs().maxCoeff() <= 1e-6);
}

TEST_CASE("ceres and the linearized loop agree where both converge", "[sauvage]") {
  const Polyline wave = bundled("wave129.obj");
  const Recipe recipe(0.05);
  const auto lin = make_solver("linearized", Backend::Optimized);
  const auto ceres = make_solver("ceres", Backend::Optimized, "{length_tolerance: 1e-11, stationarity_tolerance: 1e-8}");
  const EditStages a = run_editing_loop(wave, 7, compress(0.85, 0, 3), recipe.objective, *lin, Backend::Optimized);
  const EditStages b = run_editing_loop(wave, 7, compress(0.85, 0, 3), recipe.objective, *ceres, Backend::Optimized);
  INFO(b.solve.summary.message);
  REQUIRE(a.solve.converged());
  REQUIRE(b.solve.converged());
  CHECK(b.solve.length_error <= 1e-11);
  CHECK((a.final - b.final).cwiseAbs().maxCoeff() <= 1e-6 * scale_of(wave.points));
}

TEST_CASE("pinned edits: held exactly, and an unreachable pin is reported before solving", "[sauvage]") {
  const Polyline wave = bundled("wave129.obj");
  const Recipe recipe(0.01, /*pin_edited=*/true);
  const auto solver = make_solver("linearized", Backend::Optimized);
  const EditStages s = run_editing_loop(wave, 7, compress(0.8, 0, 2), recipe.objective, *solver, Backend::Optimized);
  REQUIRE(s.solve.converged());
  CHECK((s.final.row(128) - s.edited.row(128)).norm() <= 1e-12);

  // Endpoints pinned and pulled farther apart than the curve is long: infeasible.
  Config pin_ends(YAML::Load("{points: endpoints}"), "pin");
  const auto ends = curve_components().constraints.create("pin", Backend::Reference, pin_ends);
  Recipe r2(0.01);
  r2.objective.constraints.push_back(ends.get());
  const double length = segment_lengths(wave.points, false).sum();
  CHECK_THROWS_WITH(run_editing_loop(wave, 7, compress(1.05 * length / 2.0), r2.objective, *solver, Backend::Optimized),
                    Catch::Contains("infeasible edit") && Catch::Contains("only"));
}

TEST_CASE("bad curve input gets clear errors", "[sauvage]") {
  const Polyline wave = bundled("wave129.obj");
  const auto solver = make_solver("linearized", Backend::Optimized);
  Recipe recipe(0.5);
  recipe.objective.beta = 1.5;
  CHECK_THROWS_WITH(run_editing_loop(wave, 7, compress(0.9), recipe.objective, *solver, Backend::Optimized),
                    Catch::Contains("outside [0, 1]"));
  recipe.objective.beta = 0.5;
  CHECK_THROWS_WITH(run_editing_loop(wave, 7, compress(0.9, 8), recipe.objective, *solver, Backend::Optimized),
                    Catch::Contains("edit level e = 8"));
  CHECK_THROWS_WITH(run_editing_loop(wave, 7, compress(0.9, 2, 7), recipe.objective, *solver, Backend::Optimized),
                    Catch::Contains("wrinkle level w = 7"));
  CHECK_THROWS_WITH(run_editing_loop(wave, 7, compress(0.9, 3, 1), recipe.objective, *solver, Backend::Optimized),
                    Catch::Contains("[e, levels-1]"));
  Polyline odd = wave;
  odd.points.conservativeResize(128, 3);
  CHECK_THROWS_WITH(run_editing_loop(odd, 7, compress(0.9), recipe.objective, *solver, Backend::Optimized),
                    Catch::Contains("2^n·k + 1"));
  Polyline repeated = wave;
  repeated.points.row(5) = repeated.points.row(4);
  CHECK_THROWS_WITH(run_editing_loop(repeated, 7, compress(0.9), recipe.objective, *solver, Backend::Optimized),
                    Catch::Contains("segment 4") && Catch::Contains("zero length"));
  CurveEdit far = compress(0.9);
  far.moves[0].index = 5;
  CHECK_THROWS_WITH(run_editing_loop(wave, 7, far, recipe.objective, *solver, Backend::Optimized),
                    Catch::Contains("not on the level-e polygon"));
}

TEST_CASE("a linearized loop that cannot converge says so instead of looping", "[sauvage]") {
  const Polyline wave = bundled("wave129.obj");
  const Recipe recipe(0.01);
  const auto solver = make_solver("linearized", Backend::Optimized, "{max_solves: 2, stationarity_tolerance: 0}");
  const EditStages s = run_editing_loop(wave, 7, compress(0.5), recipe.objective, *solver, Backend::Optimized);
  CHECK_FALSE(s.solve.converged());
  CHECK(s.solve.solves == 2);
  CHECK_THAT(s.solve.summary.message, Catch::Contains("not converged after 2 solves"));
  CHECK(s.final.allFinite());
}
