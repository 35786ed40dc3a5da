// Planar curves stay planar (curve_design/curve_plane.h): the plane is found, every length
// solver keeps a planar problem in it, the second-order verdict agrees with the in-plane reduced
// Hessian computed here independently, and drags keep the original curve's lengths.
#include <catch2/catch.hpp>

#include <random>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/QR>

#include "fairshape/core/config.h"
#include "fairshape/curve_design/curve_metrics.h"
#include "fairshape/curve_design/curve_plane.h"
#include "fairshape/curve_design/editing_loop.h"
#include "fairshape/curve_design/length_manifold.h"
#include "fairshape/curve_design/second_order.h"
#include "fairshape/curve_design/self_crossings.h"
#include "fairshape/io/mesh_io.h"

using namespace fairshape;

namespace {

Polyline bundled(const std::string& name) { return read_polyline(std::string(FAIRSHAPE_SOURCE_DIR) + "/data/curves/" + name); }

std::unique_ptr<LengthSolver> make_solver(const std::string& type) {
  Config c(YAML::Load("{max_solves: 5000}"), "solver");
  auto s = curve_components().solvers.create(type, Backend::Optimized, c);
  return s;
}

struct Recipe {
  std::unique_ptr<CurveEnergy> bending;
  std::vector<std::unique_ptr<CurveConstraintKind>> kinds;
  CurveObjective objective;
  explicit Recipe(double beta) {
    Config none;
    bending = curve_components().energies.create("bending", Backend::Reference, none);
    kinds.push_back(curve_components().constraints.create("segment_lengths", Backend::Reference, none));
    objective.smoothness = bending.get();
    objective.beta = beta;
    for (const auto& k : kinds) objective.constraints.push_back(k.get());
  }
};

CurveEdit compress(double scale, int w, SolveRegion region) {
  CurveEdit edit;
  edit.edit_level = 0;
  edit.wrinkle_level = w;
  edit.options.solve_region = region;
  CurveMove mv;
  mv.index = -1;
  mv.chord_scale = scale;
  edit.moves.push_back(mv);
  return edit;
}

// The bundled wave turned into a tilted plane and shaken inside it: nothing about the plane
// is axis-aligned, and the noise gives wrinkles that want to buckle out of it.
Polyline tilted_noisy_wave() {
  Polyline c = bundled("wave129.obj");
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0, 2e-3);
  for (Eigen::Index i = 0; i < c.points.rows(); ++i) {
    c.points(i, 0) += noise(rng);
    c.points(i, 1) += noise(rng);
    c.points(i, 2) = 0;
  }
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.7, Vec3(1, 2, 0.5).normalized()).toRotationMatrix());
  c.points = (c.points * R.transpose()).rowwise() + Eigen::RowVector3d(0.3, -0.2, 1.1);
  return c;
}

// The smallest and largest |eigenvalue| of the reduced Hessian over in-plane directions only,
// computed densely from the problem without in-plane rows (plane: free): E maps 2 in-plane
// coordinates per point to 3-D, Z spans null(J E).
std::pair<double, double> in_plane_reduced_hessian(const LengthProblem& p, const MatrixX3& X, const CurvePlane& plane) {
  const int N = p.n_points();
  const Vec3 e1 = plane.normal.unitOrthogonal(), e2 = plane.normal.cross(e1);
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(3 * N, 2 * N);
  for (int i = 0; i < N; ++i) {
    E.block<3, 1>(3 * i, 2 * i) = e1;
    E.block<3, 1>(3 * i, 2 * i + 1) = e2;
  }
  const Eigen::VectorXd lambda = least_squares_multipliers(p, X);
  const Eigen::MatrixXd W = Eigen::MatrixXd(lagrangian_hessian(p, X, lambda));
  const Eigen::MatrixXd JE = Eigen::MatrixXd(constraint_jacobian(p.rows(X), N)) * E;
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(JE.transpose());
  const Eigen::MatrixXd Q = qr.householderQ();
  const Eigen::MatrixXd Z = Q.rightCols(2 * N - qr.rank());
  const Eigen::MatrixXd R = Z.transpose() * E.transpose() * W * E * Z;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (R + R.transpose()));
  return {eig.eigenvalues()(0), eig.eigenvalues().cwiseAbs().maxCoeff()};
}

}  // namespace

TEST_CASE("curve plane: found in any orientation, rejected off it, measured on the points", "[sauvage][plane]") {
  const Polyline c = tilted_noisy_wave();
  const CurvePlane plane = fit_plane({&c.points});
  CHECK(plane.planar);
  CHECK(distance_from_plane(c.points, plane) < 1e-13 * plane.size);
  MatrixX3 lifted = c.points;
  lifted(40, 0) += 1e-6 * plane.size * plane.normal.x();
  lifted(40, 1) += 1e-6 * plane.size * plane.normal.y();
  lifted(40, 2) += 1e-6 * plane.size * plane.normal.z();
  CHECK_FALSE(fit_plane({&lifted}).planar);
  const Polyline helix = bundled("helix257.obj");
  CHECK_FALSE(fit_plane({&helix.points}).planar);
  // A straight line: planar, in the plane through it closest to z (where explicit wrinkles bulge).
  MatrixX3 line = MatrixX3::Zero(9, 3);
  line.col(0) = Eigen::VectorXd::LinSpaced(9, 0, 1);
  const CurvePlane through = fit_plane({&line});
  CHECK(through.planar);
  CHECK(std::abs(through.normal.z()) == Approx(1.0));
}

TEST_CASE("curve plane: in-plane rows skip pinned points and one point per tangent-joined group", "[sauvage][plane]") {
  const PinnedPoints pins({0, 8}, MatrixX3::Zero(2, 3));
  MatrixX3 t(1, 3);
  t << 1, 0, 0;
  const FixedTangents tangent({4}, t, 9, false);  // chord 3-5: one group, one row (at 3)
  const std::vector<int> rows = in_plane_points(9, {&pins, &tangent});
  CHECK(rows == std::vector<int>{1, 2, 3, 4, 6, 7});
}

TEST_CASE("planar curves stay planar with every length solver, the verdict the in-plane reduced Hessian's",
          "[sauvage][plane]") {
  const Polyline wave = tilted_noisy_wave();
  const CurvePlane input = fit_plane({&wave.points});
  REQUIRE(input.planar);
  const Recipe recipe(0.5);
  for (const std::string& type : curve_components().solvers.names()) {
    for (SolveRegion region : {SolveRegion::Curve, SolveRegion::Support}) {
      CAPTURE(type, region == SolveRegion::Curve ? "curve" : "support");
      const auto solver = make_solver(type);
      const CurveEdit edit = compress(0.8, 3, region);
      const EditStages s = run_editing_loop(wave, 7, edit, recipe.objective, *solver, Backend::Optimized);
      REQUIRE(s.solved_in_plane);
      CHECK(distance_from_plane(s.final, input) <= 1e-12 * input.size);
      // Lengths as far as the solver claims them (the projection baseline is a penalty method).
      if (s.solve.converged())
        CHECK(measure_curve(s.final, false, segment_lengths(wave.points, false), s.attracting).length_error_max < 1e-9);
      if (region == SolveRegion::Curve && (s.solve.converged() || s.solve.summary.termination == Termination::NotAMinimum)) {
        CurveEdit free = edit;
        free.options.plane = PlaneMode::Free;
        const PreparedCurveEdit unpinned = prepare_editing_loop(wave, 7, free, recipe.objective, Backend::Optimized);
        const auto [lowest, largest] = in_plane_reduced_hessian(*unpinned.problem, s.final, input);
        CAPTURE(lowest, largest, s.solve.summary.message);
        const bool minimum = lowest >= -kSecondOrderTolerance * largest;
        CHECK(minimum == s.solve.converged());
      }
    }
  }
}

TEST_CASE("plane: free gives a planar curve three unknowns per point, a lifted edit is solved in 3-D", "[sauvage][plane]") {
  const Polyline wave = bundled("wave129.obj");
  const Recipe recipe(0.5);
  const auto solver = make_solver("linearized");
  CurveEdit free = compress(0.8, -1, SolveRegion::Curve);
  free.options.plane = PlaneMode::Free;
  CHECK_FALSE(prepare_editing_loop(wave, 7, free, recipe.objective, Backend::Optimized).stages.solved_in_plane);
  CurveEdit lifted = compress(0.8, -1, SolveRegion::Curve);
  lifted.moves.front().chord_scale = 0;
  lifted.moves.front().offset = Vec3(-0.1, 0, 0.05);
  CHECK_FALSE(prepare_editing_loop(wave, 7, lifted, recipe.objective, Backend::Optimized).stages.solved_in_plane);
}

TEST_CASE("a drag of 20 steps keeps the original curve's lengths, not the previous step's", "[sauvage][plane]") {
  const Polyline wave = bundled("wave129.obj");
  const Recipe recipe(0.1);
  const auto solver = make_solver("linearized");
  const Eigen::VectorXd original = segment_lengths(wave.points, false);
  Polyline current = wave;
  for (const CurveEdit& step : drag_steps(compress(0.8, 3, SolveRegion::Support), 20)) {
    const EditStages s = run_editing_loop(current, 7, step, recipe.objective, *solver, Backend::Optimized, &wave);
    REQUIRE(s.solve.converged());
    current.points = s.final;
    CAPTURE(step.drag_step);
    CHECK(measure_curve(current.points, false, original, s.attracting).length_error_max <= solver->tolerances().length);
  }
}

TEST_CASE("self-crossings: the grid count equals the all-pairs count", "[sauvage][plane]") {
  CurvePlane xy;
  xy.planar = true;
  MatrixX3 bow(4, 3);
  bow << 0, 0, 0, 1, 1, 0, 1, 0, 0, 0, 1, 0;
  CHECK(count_self_crossings(bow, true, xy) == 1);   // segments 0 and 2 cross; the closing one crosses none
  CHECK(count_self_crossings(bow, false, xy) == 1);
  MatrixX3 square(4, 3);
  square << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  CHECK(count_self_crossings(square, true, xy) == 0);  // adjacent segments share their corner: not a crossing
  // A random walk crosses itself many times; every crossing is found, none twice.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  MatrixX3 walk = MatrixX3::Zero(300, 3);
  for (int i = 1; i < 300; ++i) walk.row(i) = walk.row(i - 1) + Eigen::RowVector3d(u(rng), u(rng) * (i % 7 == 0 ? 5 : 1), 0);
  for (bool closed : {false, true}) {
    const int n = 300, m = closed ? n : n - 1;
    int brute = 0;
    const CurvePlane plane = fit_plane({&walk});
    const Vec3 e1 = plane.normal.unitOrthogonal(), e2 = plane.normal.cross(e1);
    const auto at = [&](int i) {
      const Vec3 x = walk.row(i % n).transpose() - plane.origin;
      return Eigen::Vector2d(x.dot(e1), x.dot(e2));
    };
    const auto orient = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
      return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    };
    for (int s = 0; s < m; ++s)
      for (int t = 0; t < s - 1; ++t) {
        if (closed && s == m - 1 && t == 0) continue;
        const auto a = at(s), b = at(s + 1), c = at(t), d = at(t + 1);
        brute += orient(a, b, c) * orient(a, b, d) < 0 && orient(c, d, a) * orient(c, d, b) < 0;
      }
    CAPTURE(closed);
    CHECK(brute > 10);
    CHECK(count_self_crossings(walk, closed, plane) == brute);
  }
}
