// A x = B on B's independent columns only (solver/independent_columns.h): a single
// handle's right-hand side has rank 1, and the combined solutions are the block solve's.
#include <catch2/catch.hpp>

#include <random>

#include "fairshape/experiment/components.h"
#include "fairshape/problem/constrained_system.h"
#include "fairshape/solver/independent_columns.h"

using namespace fairshape;

namespace {

// A 1-D Laplacian plus a small shift: SPD, and CG needs many iterations on it.
SparseMatrix spd(int n) {
  Triplets t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.001);
    if (i + 1 < n) t.emplace_back(i, i + 1, -1.0), t.emplace_back(i + 1, i, -1.0);
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

Eigen::MatrixXd rank_one(int n) {  // the cow's pattern: y exactly 0, z a multiple of x
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n, 3);
  for (int i = 0; i < n; ++i) B(i, 0) = normal(rng);
  B.col(2) = 0.533 * B.col(0);
  return B;
}

std::unique_ptr<Solver> cg() {
  Config cfg(YAML::Load("{tolerance: 1.0e-12, max_iterations: 100000}"), "solver");
  return components().solvers.create("conjugate_gradient", Backend::Optimized, cfg);
}

}  // namespace

TEST_CASE("dependent columns: exactly dependent ones are found, nearly dependent ones are not",
          "[solver][independent_columns]") {
  const Eigen::MatrixXd B = rank_one(200);
  const auto d = dependent_columns(B);
  REQUIRE(d);
  CHECK(d->independent.size() == 1);
  CHECK((B.col(d->independent[0]) * d->combination - B).norm() < 1e-14 * B.norm());
  Eigen::MatrixXd nearly = B;
  nearly(7, 2) += 1e-8;  // z is no multiple of x any more: both are solved, y = 0 still is not
  const auto two = dependent_columns(nearly);
  REQUIRE(two);
  CHECK(two->independent.size() == 2);
  nearly(9, 1) = 1e-9;  // and y is no longer 0: every column is needed
  CHECK_FALSE(dependent_columns(nearly));
  CHECK_FALSE(dependent_columns(Eigen::MatrixXd::Random(50, 3)));
  CHECK_FALSE(dependent_columns(B.col(0)));  // one column: nothing to save
}

TEST_CASE("independent columns: the block solve's answer at the cost of one column",
          "[solver][independent_columns]") {
  const int n = 400;
  const SparseMatrix A = spd(n);
  const Eigen::MatrixXd B = rank_one(n);
  const auto block_solver = cg(), reduced_solver = cg();
  Eigen::MatrixXd block = Eigen::MatrixXd::Zero(n, 3), reduced = Eigen::MatrixXd::Zero(n, 3);
  const SolveSummary b = block_solver->solve(A, B, block);
  int widths = 0;
  const IterationCallback seen = [&](const IterationRecord& r) {
    widths = static_cast<int>(r.x->cols());
    return true;
  };
  const SolveSummary r = solve_independent_columns(*reduced_solver, A, B, reduced, seen);
  REQUIRE(b.succeeded());
  REQUIRE(r.succeeded());
  CHECK(relative_error(reduced, block) < 1e-10);
  CHECK(relative_residual(A, B, reduced) < 1e-11);
  CHECK(r.residual == Approx(relative_residual(A, B, reduced)));
  CHECK_THAT(r.message, Catch::Contains("solved 1 independent of 3"));
  CHECK(widths == 3);  // the callback sees every column
  // One column's iterations (CG on a block runs until the slowest column converges).
  Eigen::MatrixXd one = Eigen::MatrixXd::Zero(n, 1);
  const SolveSummary single = cg()->solve(A, B.col(0), one);
  CHECK(r.iterations == single.iterations);
}

TEST_CASE("independent columns: a start of another dependence keeps the block solve",
          "[solver][independent_columns]") {
  const int n = 300;
  const SparseMatrix A = spd(n);
  const Eigen::MatrixXd B = rank_one(n);
  Eigen::MatrixXd start = Eigen::MatrixXd::Zero(n, 3);
  start(5, 1) = 1.0;  // y is not 0 in the start
  Eigen::MatrixXd x = start;
  const SolveSummary s = solve_independent_columns(*cg(), A, B, x);
  REQUIRE(s.succeeded());
  CHECK_THAT(s.message, !Catch::Contains("independent of"));
  CHECK(relative_residual(A, B, x) < 1e-11);
  // A start of the same dependence (a drag's previous step, B scaled) is reduced.
  Eigen::MatrixXd warm = 0.5 * B;
  const SolveSummary w = solve_independent_columns(*cg(), A, B, warm);
  CHECK_THAT(w.message, Catch::Contains("solved 1 independent of 3"));
  CHECK(relative_residual(A, B, warm) < 1e-11);
}
