// A fixed total length instead of every segment's (the alternative Sauvage, Hahmann and Bonneau
// discuss in "Length preserving multiresolution editing of curves"): the
// constraint's derivatives, the bordered banded KKT solve against a dense one, Figure 1's edit
// under it (total met, segments stretched, both back ends alike, a true minimum) and bad input.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <yaml-cpp/yaml.h>

#include "fairshape/core/config.h"
#include "fairshape/core/error.h"
#include "fairshape/curve_design/ceres_length_solver.h"
#include "fairshape/curve_design/editing_loop.h"
#include "fairshape/curve_design/kkt_factor.h"
#include "fairshape/curve_design/length_manifold.h"
#include "fairshape/curve_design/reduced_eigenvalue.h"
#include "fairshape/curve_design/second_order.h"
#include "fairshape/experiment/kinds/curve/curve_run.h"
#include "fairshape/experiment/run_outputs.h"
#include "fairshape/io/mesh_io.h"
#include "test_support.h"

using namespace fairshape;
using Catch::Matchers::Contains;

namespace {

// A wavy 3-D curve of n points (closed: a wavy ring).
MatrixX3 wavy(int n, bool closed) {
  MatrixX3 X(n, 3);
  for (int i = 0; i < n; ++i) {
    const double t = closed ? 2 * M_PI * i / n : 3.0 * i / (n - 1);
    if (closed) X.row(i) << std::cos(t) * (1 + 0.1 * std::sin(5 * t)), std::sin(t), 0.2 * std::cos(3 * t);
    else X.row(i) << t, 0.3 * std::sin(2.1 * t), 0.1 * std::cos(1.3 * t);
  }
  return X;
}

Eigen::MatrixXd dense_hessian(const CurveConstraint& c, const MatrixX3& X) {
  Triplets t;
  c.add_row_hessian(0, 1.0, X, t);
  SparseMatrix H(3 * X.rows(), 3 * X.rows());
  H.setFromTriplets(t.begin(), t.end());
  return Eigen::MatrixXd(H);
}

// Bending + a pull to X itself, the total length asked `scale` × X's, both ends pinned.
std::unique_ptr<LengthProblem> pinned_total_problem(const MatrixX3& X, double scale) {
  const int n = static_cast<int>(X.rows());
  std::vector<CurveStencil> attractor;
  for (int i = 0; i < n; ++i) attractor.push_back({1, {i, 0, 0}, {1.0, 0, 0}, i});
  std::vector<WeightedStencils> energies{{"bending", 1.0, bending_stencils(n, false)}, {"attractor", 0.3, attractor}};
  const Eigen::VectorXd l = segment_lengths(X, false);
  std::vector<std::unique_ptr<CurveConstraint>> constraints;
  MatrixX3 ends(2, 3);
  ends << X.row(0), X.row(n - 1);
  constraints.push_back(std::make_unique<PinnedPoints>(std::vector<int>{0, n - 1}, ends));
  constraints.push_back(std::make_unique<TotalLength>(l, scale * l.sum(), false));
  return std::make_unique<LengthProblem>(X, false, std::move(energies), std::move(constraints), l);
}

struct TotalRecipe {
  std::unique_ptr<CurveEnergy> bending;
  std::unique_ptr<CurveConstraintKind> total;
  CurveObjective objective;
  explicit TotalRecipe(double beta) {
    Config none;
    bending = curve_components().energies.create("bending", Backend::Reference, none);
    total = curve_components().constraints.create("total_length", Backend::Reference, none);
    objective.smoothness = bending.get();
    objective.beta = beta;
    objective.constraints.push_back(total.get());
  }
};

// Figure 1's edit: the wave's right end pulled to 70 % of the chord at the coarsest level.
CurveEdit compress_wave() {
  CurveEdit edit;
  CurveMove mv;
  mv.index = -1;
  mv.chord_scale = 0.7;
  edit.moves.push_back(mv);
  edit.options.solve_region = SolveRegion::Curve;
  return edit;
}

std::unique_ptr<LengthSolver> make_solver(const std::string& type, Backend b, const std::string& yaml) {
  Config c(YAML::Load(yaml), "solver");
  return curve_components().solvers.create(type, b, c);
}

YAML::Node total_config(const std::string& constraints, const std::string& solver = "trust_region") {
  return YAML::Load(R"(
name: total
input: {curve: data/curves/wave129.obj}
edits: [{level: 0, moves: [{index: -1, chord_scale: 0.7}]}]
editing: {solve_region: curve}
optimization:
  beta: 0.01
  constraints: )" + constraints + R"(
  solver: {type: )" + solver + R"(, length_tolerance: 1.0e-12, max_solves: 5000}
output: {vtk: none, final_curve: true}
)");
}

MetricRow run_config(const YAML::Node& cfg, const std::string& id) {
  const auto dir = test::scratch_dir("total_length_" + id);
  create_run_folders(dir.string());
  CurveRunSpec spec = CurveRunSpec::from_config(cfg, {test::source_path("")});
  RunTables tables;
  return execute_curve_run(spec, RunOutputs{dir.string(), id, true, &tables});
}

std::string refusal(const YAML::Node& cfg) {
  try {
    (void)CurveRunSpec::from_config(cfg, {test::source_path("")});
  } catch (const InvalidConfig& e) {
    return e.what();
  }
  return "(accepted)";
}

}  // namespace

TEST_CASE("total length: value, gradient and Hessian match finite differences", "[sauvage][total_length]") {
  for (const bool closed : {false, true}) {
    const MatrixX3 X = wavy(9, closed);
    const Eigen::VectorXd l = segment_lengths(X, closed);
    const TotalLength c(l, 0.8 * l.sum(), closed);
    const ConstraintRow r = c.evaluate(0, X);
    REQUIRE(r.dense);
    CHECK(r.value == Approx(0.2 * l.sum()).epsilon(1e-13));
    const Eigen::MatrixXd H = dense_hessian(c, X);
    CHECK((H - H.transpose()).norm() < 1e-14);
    const double h = 1e-6;
    for (int i = 0; i < X.rows(); ++i)
      for (int d = 0; d < 3; ++d) {
        MatrixX3 Xp = X, Xm = X;
        Xp(i, d) += h;
        Xm(i, d) -= h;
        CHECK(r.grad(i)[d] == Approx((c.evaluate(0, Xp).value - c.evaluate(0, Xm).value) / (2 * h)).margin(1e-8));
        const MatrixX3 dg = (c.evaluate(0, Xp).dense_gradient - c.evaluate(0, Xm).dense_gradient) / (2 * h);
        for (int j = 0; j < X.rows(); ++j)
          for (int e = 0; e < 3; ++e) CHECK(H(3 * j + e, 3 * i + d) == Approx(dg(j, e)).margin(1e-6));
      }
    // The pattern does not depend on X: an axis-aligned curve emits as many entries.
    Triplets a, b;
    c.add_row_hessian(0, 1.0, X, a);
    MatrixX3 straight = MatrixX3::Zero(X.rows(), 3);
    straight.col(0) = Eigen::VectorXd::LinSpaced(X.rows(), 0, 1);
    c.add_row_hessian(0, 1.0, straight, b);
    CHECK(a.size() == b.size());
  }
}

TEST_CASE("total length: the bordered banded KKT solve equals a dense KKT solve, inertia included",
          "[sauvage][total_length][kkt]") {
  const MatrixX3 X = wavy(40, false);
  const auto p = pinned_total_problem(X, 1.1);
  const std::vector<ConstraintRow> rows = p->rows(X);
  const int n = 3 * p->n_points(), m = p->n_constraint_rows();
  REQUIRE(p->has_dense_rows());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd rhs(n + m);
  for (Eigen::Index i = 0; i < rhs.size(); ++i) rhs[i] = u(rng);
  // λ of the pins random, the total's positive (W positive definite) or strongly negative (W
  // indefinite on the tangent space: the inertia must count it).
  for (const double total_lambda : {0.5, -40.0}) {
    Eigen::VectorXd lambda(m);
    for (int r = 0; r < m; ++r) lambda[r] = u(rng);
    lambda[m - 1] = total_lambda;
    for (const double shift : {0.0, 1e-3}) {
      SparseMatrix W = lagrangian_hessian(*p, X, lambda);
      for (int i = 0; i < n; ++i) W.coeffRef(i, i) += shift;
      const Eigen::MatrixXd J = Eigen::MatrixXd(constraint_jacobian(rows, p->n_points()));
      Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + m, n + m);
      K.topLeftCorner(n, n) = Eigen::MatrixXd(W);
      K.topRightCorner(n, m) = J.transpose();
      K.bottomLeftCorner(m, n) = J;
      const Eigen::VectorXd expected = K.fullPivLu().solve(rhs);
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, Eigen::EigenvaluesOnly);
      const int negative = static_cast<int>((eig.eigenvalues().array() < 0).count());
      for (const Backend b : {Backend::Optimized, Backend::Reference}) {
        INFO("λ_total " << total_lambda << ", shift " << shift << ", " << to_string(b));
        const auto kkt = make_kkt_factor(*p, b, KktMethod::Direct, 0);
        REQUIRE(kkt->factor(X, rows, &lambda, shift));
        CHECK((kkt->solve(rhs) - expected).norm() <= 1e-10 * expected.norm());
        if (b == Backend::Optimized) CHECK(kkt->negative_pivots() == negative);
      }
      if (total_lambda < 0) CHECK(negative > m);  // the indefinite case is one
      // MINRES on the banded part, bordered the same way.
      const auto minres = make_kkt_factor(*p, Backend::Optimized, KktMethod::Minres, 1e-14);
      REQUIRE(minres->factor(X, rows, &lambda, shift));
      CHECK((minres->solve(rhs) - expected).norm() <= 1e-7 * expected.norm());
    }
  }
}

TEST_CASE("total length on Figure 1's edit: total met, segments stretched, back ends alike, a true minimum",
          "[sauvage][total_length]") {
  const Polyline wave = read_polyline(test::data_path("curves/wave129.obj"));
  const double size = (wave.points.colwise().maxCoeff() - wave.points.colwise().minCoeff()).norm();
  const TotalRecipe recipe(0.01);
  const std::string tol = "{length_tolerance: 1.0e-12, stationarity_tolerance: 1.0e-8, max_solves: 5000}";
  for (const std::string type : {"trust_region", "linearized"}) {
    INFO(type);
    EditStages ends[2];
    for (const Backend b : {Backend::Reference, Backend::Optimized}) {
      const auto solver = make_solver(type, b, tol);
      ends[b == Backend::Optimized] = run_editing_loop(wave, 7, compress_wave(), recipe.objective, *solver, b);
    }
    for (const EditStages& s : ends) {
      INFO(s.solve.summary.message);
      CHECK(s.length_mode == LengthMode::Total);
      CHECK(s.total_length_asked == Approx(segment_lengths(wave.points, false).sum()).epsilon(1e-14));
      // The total is kept to the tolerance (its rounding floor, 7e-13 here) ...
      const double total = segment_lengths(s.final, false).sum();
      CHECK(std::abs(total - s.total_length_asked) / s.total_length_asked < 1e-12);
      CHECK(s.solve.length_error < 1e-12);
      // ... while the segments are not: they stretch and shrink by percents.
      const Eigen::VectorXd stretch = segment_lengths(s.final, false).cwiseQuotient(segment_lengths(wave.points, false));
      CHECK(stretch.maxCoeff() - stretch.minCoeff() > 0.02);
    }
    // Reference = optimized.
    CHECK((ends[0].final - ends[1].final).cwiseAbs().maxCoeff() < 1e-8 * size);
    CHECK(ends[0].solve.summary.termination == ends[1].solve.summary.termination);
    if (type == "trust_region") REQUIRE(ends[1].solve.converged());
  }

  // The trust region's answer is a minimum, checked without the solver: its reduced Hessian
  // (the total length's Hessian included) has no negative eigenvalue, F along the softest
  // tangent direction (retracted onto the total length) curves as that eigenvalue says — which
  // it would not without the constraint's Hessian — and random retracted moves never lower F.
  const auto solver = make_solver("trust_region", Backend::Optimized, tol);
  PreparedCurveEdit prepared = prepare_editing_loop(wave, 7, compress_wave(), recipe.objective, Backend::Optimized);
  const LengthProblem& p = *prepared.problem;
  const LengthSolveReport rep = solver->solve(p, prepared.stages.attracting);
  REQUIRE(rep.converged());
  const MatrixX3& X = rep.points;
  const SecondOrderCheck so = check_second_order(p, X);
  REQUIRE(so.checked);
  CHECK(so.min_eigenvalue >= 0);
  CHECK(rep.min_reduced_hessian_eig == Approx(so.min_eigenvalue).epsilon(kReducedEigenvalueTolerance));  // the inertia bracket's width
  const double F = p.objective(X), t = 1e-3;
  const auto along = [&](const MatrixX3& d, double h) { return p.objective(retract(p, X + h * d, 1e-15, 100).points); };
  const double curvature = (along(so.direction, t) + along(so.direction, -t) - 2 * F) / (t * t);
  const Eigen::Map<const Eigen::VectorXd> z(so.direction.data(), so.direction.size());
  const Eigen::VectorXd zero_lambda = Eigen::VectorXd::Zero(p.n_constraint_rows());
  const double without_constraint_hessian = z.dot(lagrangian_hessian(p, X, zero_lambda) * z);
  INFO("λ_min " << so.min_eigenvalue << ", F'' along it " << curvature << ", without ∇²f " << without_constraint_hessian);
  CHECK(curvature == Approx(so.min_eigenvalue).epsilon(0.02));
  CHECK(std::abs(without_constraint_hessian - so.min_eigenvalue) > 0.1 * std::abs(so.min_eigenvalue));
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  const SparseMatrix J = constraint_jacobian(p.rows(X), p.n_points());
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd d(3 * p.n_points());
    for (Eigen::Index i = 0; i < d.size(); ++i) d[i] = g(rng);
    const Eigen::VectorXd Jd = J * d;
    d -= Eigen::VectorXd(J.transpose() * Eigen::VectorXd((Eigen::MatrixXd(J * J.transpose())).ldlt().solve(Jd)));
    d *= 1e-2 * size / d.norm();
    CHECK(along(Eigen::Map<const MatrixX3>(d.data(), p.n_points(), 3), 1.0) >= F * (1 - 1e-12));
  }
}

TEST_CASE("total length from a config: runs.csv says what was asked and reached, a given value is met",
          "[sauvage][total_length]") {
  const MetricRow kept = run_config(total_config("[{type: total_length}]"), "kept");
  INFO(kept.at("message"));
  REQUIRE(kept.at("termination") == "converged");
  CHECK(kept.at("length_constraint") == "total_length");
  CHECK(std::stod(kept.at("total_length_error")) < 1e-12);
  CHECK(std::stod(kept.at("length_error_max")) > 0.01);  // segments stretched
  CHECK(std::stod(kept.at("segment_stretch_max")) > 1.0);
  CHECK(std::stod(kept.at("segment_stretch_min")) < 1.0);
  CHECK(std::stod(kept.at("min_reduced_hessian_eig")) >= 0);
  const double reference = segment_lengths(read_polyline(test::data_path("curves/wave129.obj")).points, false).sum();
  CHECK(std::stod(kept.at("total_length_asked")) == Approx(reference).epsilon(1e-9));
  // The paper's segment lengths report the same columns: every segment kept, stretch 1.
  const MetricRow segments = run_config(total_config("[{type: segment_lengths}]"), "segments");
  REQUIRE(segments.at("termination") == "converged");
  CHECK(segments.at("length_constraint") == "segment_lengths");
  CHECK(std::abs(std::stod(segments.at("segment_stretch_max")) - 1) < 1e-11);
  CHECK(std::stod(segments.at("total_length_error")) < 1e-11);
  // A total 5 % longer than the reference's, and the ends pinned where the edit put them.
  const MetricRow longer =
      run_config(total_config("[{type: total_length, value: " + std::to_string(1.05 * reference) + "}, {type: pin, points: endpoints}]"),
                 "longer");
  INFO(longer.at("message"));
  REQUIRE(longer.at("termination") == "converged");
  CHECK(std::stod(longer.at("total_length_asked")) == Approx(1.05 * reference).epsilon(1e-6));
  CHECK(std::stod(longer.at("total_length_error")) < 1e-12);
}

TEST_CASE("total length: bad values and combinations it cannot take are refused, naming the key", "[sauvage][total_length]") {
  CHECK_THAT(refusal(total_config("[{type: total_length, value: 0}]")),
             Contains("optimization.constraints[0].value: 0 is not a length; give a positive finite number"));
  CHECK_THAT(refusal(total_config("[{type: total_length, value: -2.5}]")), Contains("value: -2.5 is not a length"));
  CHECK_THAT(refusal(total_config("[{type: total_length, value: .nan}]")), Contains("value: expected finite numbers"));
  CHECK_THAT(refusal(total_config("[{type: total_length, value: .inf}]")), Contains("value: expected finite numbers"));
  CHECK_THAT(refusal(total_config("[{type: total_length, length: 3}]")), Contains("length"));
  CHECK_THAT(refusal(total_config("[{type: segment_lengths}, {type: total_length}]")),
             Contains("total_length and segment_lengths together"));
  CHECK_THAT(refusal(total_config("[{type: total_length}, {type: total_length}]")), Contains("a second total_length"));
  CHECK_THAT(refusal(total_config("[{type: pin}]")), Contains("or {type: total_length}"));
  for (const std::string solver : {"ceres", "projection"})
    CHECK_THAT(refusal(total_config("[{type: total_length}]", solver)),
               Contains("optimization.solver.type: " + solver + " does not take the total_length constraint") &&
                   Contains("the solvers that do: linearized, trust_region"));
  YAML::Node support = total_config("[{type: total_length}]");
  support["editing"]["solve_region"] = "support";
  CHECK_THAT(refusal(support), Contains("set editing.solve_region: curve"));
  // A total shorter than the pinned ends' distance cannot be met: said before solving.
  const MetricRow short_total = run_config(total_config("[{type: total_length, value: 1.0}, {type: pin, points: endpoints}]"), "short");
  CHECK(short_total.at("termination") == "invalid_input");
  CHECK_THAT(short_total.at("message"), Contains("infeasible edit") && Contains("total length is to be 1"));

  // The library refuses the same things (for callers without a config).
  const MatrixX3 X = wavy(9, false);
  const Eigen::VectorXd l = segment_lengths(X, false);
  CHECK_THROWS_WITH(TotalLength(l, 0.0, false), Contains("positive finite"));
  CHECK_THROWS_WITH(TotalLength(l, std::nan(""), false), Contains("positive finite"));
  std::vector<std::unique_ptr<CurveConstraint>> both;
  both.push_back(std::make_unique<SegmentLengths>(l, false));
  both.push_back(std::make_unique<TotalLength>(l, l.sum(), false));
  CHECK_THROWS_WITH(LengthProblem(X, false, {{"bending", 1.0, bending_stencils(9, false)}}, std::move(both)),
                    Contains("segment_lengths and total_length together"));
  const auto p = pinned_total_problem(X, 1.1);
  const LengthSolveReport ceres = CeresLengthSolver(CeresOptions{}).solve(*p, X);
  CHECK(ceres.summary.termination == Termination::InvalidInput);
  CHECK_THAT(ceres.summary.message, Contains("solvers that do: linearized, trust_region"));
}

TEST_CASE("pins no curve of the reference lengths can meet: trust_region ends infeasible, saying so", "[sauvage][infeasible]") {
  // The first two points pinned half their segment's length apart: the segment cannot keep its
  // length. (Pins farther apart than the curve between them are refused before any solve.)
  const int n = 17;
  const MatrixX3 X = wavy(n, false);
  const Eigen::VectorXd l = segment_lengths(X, false);
  std::vector<WeightedStencils> energies{{"bending", 1.0, bending_stencils(n, false)}};
  std::vector<std::unique_ptr<CurveConstraint>> constraints;
  MatrixX3 ends(2, 3);
  ends << X.row(0), X.row(0) + 0.5 * (X.row(1) - X.row(0));
  constraints.push_back(std::make_unique<PinnedPoints>(std::vector<int>{0, 1}, ends));
  constraints.push_back(std::make_unique<SegmentLengths>(l, false));
  const LengthProblem p(X, false, std::move(energies), std::move(constraints), l);
  for (Backend b : {Backend::Reference, Backend::Optimized}) {
    const auto solver = make_solver("trust_region", b, "{length_tolerance: 1.0e-10, max_solves: 500}");
    const LengthSolveReport rep = solver->solve(p, X);
    INFO(to_string(b) << ": " << rep.summary.message);
    CHECK(rep.summary.termination == Termination::Infeasible);
    CHECK_FALSE(rep.summary.succeeded());
    CHECK_THAT(rep.summary.message, Contains("no curve of the reference lengths"));
    CHECK(std::max(rep.length_error, rep.pin_error) > 1e-3);  // not passed off as meeting lengths and pins
    CHECK(rep.points.allFinite());
  }
}
