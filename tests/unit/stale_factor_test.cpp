// Solver::solve(A, …) answers for A itself (solver/solver.h): after analyze(A1), a solve with
// another matrix of the same size — new values, a new sparsity pattern, or the same buffer
// refilled — re-analyzes instead of reusing A1's factor, colouring or multigrid levels. Every
// solver the registry holds, on both back ends, is checked: a new solver joins by registering.
// Also: the fingerprint that tells the matrices apart, and the curve editor's KKT factor, which
// keeps a pattern built for one set of constraint rows.
#include <catch2/catch.hpp>
#include <tbb/global_control.h>

#include <cmath>
#include <random>

#include "fairshape/curve_design/kkt_factor.h"
#include "fairshape/energy/laplacian.h"
#include "fairshape/experiment/components.h"
#include "fairshape/solver/level_operators.h"
#include "fairshape/solver/matrix_fingerprint.h"
#include "fairshape/subdivision/multires_surface.h"
#include "fairshape/subdivision/subdivider.h"
#include "test_support.h"

using namespace fairshape;

namespace {

// Iterative solvers run to a relative residual of 1e-11 (kOptions); every solver, direct or
// iterative, must then meet kResidual on the matrix it was given (a stale analysis misses it by
// orders of magnitude).
constexpr const char* kOptions = "{tolerance: 1.0e-11, max_iterations: 100000}";
constexpr double kResidual = 1e-9;

// The uniform graph Laplacian (positive semi-definite) on the finest level of a Catmull-Clark
// hierarchy of a quad grid, with that hierarchy's transfer operators for the multilevel solvers
// (set up as tests/unit/multigrid_test.cpp does; the conformance test skips those solvers).
struct GridHierarchy {
  SparseMatrix laplacian;
  std::shared_ptr<LevelOperators> ops = std::make_shared<LevelOperators>();
};

const GridHierarchy& grid_hierarchy() {
  static const GridHierarchy h = [] {
    const int levels = 2;
    const MultiresSurface surface(test::grid(4), SubdivisionOptions{}, levels, Backend::Optimized);
    GridHierarchy out;
    out.laplacian = -graph_laplacian(surface.mesh(levels), LaplacianWeights::Uniform);
    for (int l = 0; l < levels; ++l) out.ops->prolongation.push_back(surface.subdivision_operator(l));
    for (int l = 0; l <= levels; ++l)
      out.ops->singular.push_back(extraordinary_vertices(surface.mesh(l), SchemeType::CatmullClark));
    out.ops->positions = surface.mesh(levels).positions();  // petsc_gamg's linear near-null space
    return out;
  }();
  return h;
}

SparseMatrix identity(Eigen::Index n) {
  SparseMatrix I(n, n);
  I.setIdentity();
  return I;
}

// scale · L + shift · I: positive definite for shift > 0, with L's pattern (L has a full diagonal).
SparseMatrix shifted_laplacian(double scale, double shift) {
  const SparseMatrix& L = grid_hierarchy().laplacian;
  SparseMatrix A = scale * L + shift * identity(L.rows());
  A.makeCompressed();
  return A;
}

// L² + shift · I: the same size as L, a wider (two-ring) pattern.
SparseMatrix squared_laplacian(double shift) {
  const SparseMatrix& L = grid_hierarchy().laplacian;
  SparseMatrix A = SparseMatrix(L * L) + shift * identity(L.rows());
  A.makeCompressed();
  return A;
}

Eigen::MatrixXd right_hand_side(Eigen::Index n) {
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u(-1, 1);
  return Eigen::MatrixXd::NullaryExpr(n, 3, [&] { return u(gen); });
}

double relative_residual_of(const SparseMatrix& A, const Eigen::MatrixXd& b, const Eigen::MatrixXd& x) {
  return (b - A * x).norm() / b.norm();
}

// Every registered (name, back end), built with tight iterative tolerances and, when it is
// multilevel, given the grid's hierarchy (every unknown kept, one coordinate block).
template <class Check>
void for_every_registered_solver(const Check& check) {
  const auto& registry = components().solvers;
  REQUIRE_FALSE(registry.entries().empty());
  for (const auto& entry : registry.entries()) {
    Config cfg(YAML::Load(kOptions), "solver");
    std::unique_ptr<Solver> solver = registry.create(entry.name, entry.backend, cfg);
    if (solver->uses_levels()) solver->set_levels(grid_hierarchy().ops, LevelSelection{});
    INFO(entry.name << " / " << to_string(entry.backend));
    check(*solver);
  }
}

// Solves A x = b from a zero start and checks that x solves A (not some earlier matrix).
void check_solves(Solver& solver, const SparseMatrix& A, const Eigen::MatrixXd& b) {
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(A.rows(), b.cols());
  const SolveSummary s = solver.solve(A, b, x);
  INFO(to_string(s.termination) << " after " << s.iterations << " iterations: " << s.message);
  CHECK(s.termination == Termination::Converged);
  CHECK(relative_residual_of(A, b, x) <= kResidual);
}

}  // namespace

TEST_CASE("every solver re-analyzes a same-size matrix with new values", "[solver][stale_factor]") {
  // Off-diagonals and diagonal both change, so no solver can get by on part of a stale copy.
  const SparseMatrix A1 = shifted_laplacian(1.0, 0.1), A2 = shifted_laplacian(3.0, 2.0);
  REQUIRE(A1.nonZeros() == A2.nonZeros());
  const Eigen::MatrixXd b = right_hand_side(A1.rows());
  for_every_registered_solver([&](Solver& solver) {
    solver.analyze(A1);
    check_solves(solver, A2, b);
    check_solves(solver, A1, b);  // and back: the analysis follows the matrix both ways
  });
}

TEST_CASE("every solver re-analyzes a same-size matrix with a new sparsity pattern", "[solver][stale_factor]") {
  const SparseMatrix A1 = shifted_laplacian(1.0, 0.1), A2 = squared_laplacian(0.5);
  REQUIRE(A1.rows() == A2.rows());
  REQUIRE(A1.nonZeros() != A2.nonZeros());
  const Eigen::MatrixXd b = right_hand_side(A1.rows());
  for_every_registered_solver([&](Solver& solver) {
    solver.analyze(A1);
    check_solves(solver, A2, b);
  });
}

TEST_CASE("a matrix refilled in place with new values is a new matrix", "[solver][stale_factor]") {
  // Callers reuse buffers: the analysis is matched by value, never by the matrix's address.
  const Eigen::MatrixXd b = right_hand_side(grid_hierarchy().laplacian.rows());
  for_every_registered_solver([&](Solver& solver) {
    SparseMatrix A = shifted_laplacian(1.0, 0.1);
    solver.analyze(A);
    const SparseMatrix A2 = shifted_laplacian(3.0, 2.0);
    std::copy(A2.valuePtr(), A2.valuePtr() + A2.nonZeros(), A.valuePtr());
    check_solves(solver, A, b);
  });
}

TEST_CASE("solve without analyze analyzes on demand", "[solver][stale_factor]") {
  const SparseMatrix A = shifted_laplacian(1.0, 0.1);
  const Eigen::MatrixXd b = right_hand_side(A.rows());
  for_every_registered_solver([&](Solver& solver) {
    check_solves(solver, A, b);
    check_solves(solver, A, b);  // the on-demand analysis is kept for the next solve
  });
}

TEST_CASE("new levels discard a multilevel solver's analysis", "[solver][stale_factor]") {
  const SparseMatrix A = shifted_laplacian(1.0, 0.1);
  const Eigen::MatrixXd b = right_hand_side(A.rows());
  int multilevel = 0;
  for_every_registered_solver([&](Solver& solver) {
    if (!solver.uses_levels()) return;
    ++multilevel;
    solver.analyze(A);
    // A hierarchy without coarse levels: solving on the old levels would hide it.
    solver.set_levels(std::make_shared<LevelOperators>(), LevelSelection{});
    Eigen::MatrixXd x = Eigen::MatrixXd::Zero(A.rows(), b.cols());
    CHECK_THROWS_AS(solver.solve(A, b, x), InvalidInput);
  });
  CHECK(multilevel > 0);
}

TEST_CASE("matrix fingerprints tell apart any change of size, pattern or value", "[solver][stale_factor]") {
  const SparseMatrix A = shifted_laplacian(1.0, 0.1);
  const MatrixFingerprint f(A);
  CHECK(MatrixFingerprint(SparseMatrix(A)) == f);  // a copy elsewhere in memory: by value
  SparseMatrix uncompressed = A;
  uncompressed.uncompress();
  CHECK(MatrixFingerprint(uncompressed) == f);
  CHECK(MatrixFingerprint() != f);
  CHECK_FALSE(MatrixFingerprint().same_pattern(f));

  SparseMatrix one_ulp = A;
  double& v = one_ulp.valuePtr()[one_ulp.nonZeros() / 2];
  v = std::nextafter(v, 2 * v);
  CHECK(MatrixFingerprint(one_ulp) != f);
  CHECK(MatrixFingerprint(one_ulp).same_pattern(f));
  SparseMatrix two_signs = A;  // a hash that keeps the sign bit on top would cancel the pair
  two_signs.valuePtr()[3] *= -1;
  two_signs.valuePtr()[7] *= -1;
  CHECK(MatrixFingerprint(two_signs) != f);

  // The same size and entry count, one entry moved.
  const auto with_entry = [](int row, int col) {
    Triplets t{{row, col, 1.0}};
    for (int i = 0; i < 5; ++i) t.emplace_back(i, i, 2.0);
    SparseMatrix M(5, 5);
    M.setFromTriplets(t.begin(), t.end());
    return M;
  };
  CHECK_FALSE(MatrixFingerprint(with_entry(0, 1)).same_pattern(MatrixFingerprint(with_entry(0, 2))));
  CHECK(MatrixFingerprint(SparseMatrix(3, 5)) != MatrixFingerprint(SparseMatrix(5, 3)));

  // Large enough to be hashed in parallel: the same fingerprint for any thread count.
  const int n = 40000;
  Triplets t;
  std::mt19937 gen(3);
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < 3; ++k) t.emplace_back(static_cast<int>(gen() % n), j, 1.0 + k);
  SparseMatrix big(n, n);
  big.setFromTriplets(t.begin(), t.end());
  REQUIRE(big.nonZeros() > 65536);
  MatrixFingerprint by_threads[2];
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    by_threads[threads - 1] = MatrixFingerprint(big);
  }
  CHECK(by_threads[0] == by_threads[1]);
}

TEST_CASE("the optimized curve KKT factor rebuilds its pattern for rows of another structure",
          "[stale_factor][sauvage]") {
  // A wave of 12 points under bending and a pull towards itself, its segment lengths kept.
  const int n = 12;
  MatrixX3 X(n, 3);
  for (int i = 0; i < n; ++i) X.row(i) << i, std::sin(0.7 * i), 0.1 * i;
  std::vector<CurveStencil> attractor;
  for (int i = 0; i < n; ++i) attractor.push_back({1, {i, 0, 0}, {1.0, 0, 0}, i});
  std::vector<WeightedStencils> energies{{"bending", 1.0, bending_stencils(n, false)}, {"attractor", 0.5, attractor}};
  std::vector<std::unique_ptr<CurveConstraint>> constraints;
  constraints.push_back(std::make_unique<SegmentLengths>(segment_lengths(X, false), false));
  const LengthProblem p(X, false, std::move(energies), std::move(constraints));
  const std::vector<ConstraintRow> rows = p.rows(X);
  const std::vector<ConstraintRow> reversed(rows.rbegin(), rows.rend());  // each row touches other points
  const auto banded = make_kkt_factor(p, Backend::Optimized, KktMethod::Direct, 0);
  const auto reference = make_kkt_factor(p, Backend::Reference, KktMethod::Direct, 0);
  REQUIRE(banded->factor(X, rows, nullptr));
  REQUIRE(banded->factor(X, reversed, nullptr));
  REQUIRE(reference->factor(X, reversed, nullptr));
  const Eigen::VectorXd rhs = right_hand_side(3 * n + p.n_constraint_rows()).col(0);
  const Eigen::VectorXd expected = reference->solve(rhs);
  CHECK((banded->solve(rhs) - expected).norm() <= 1e-9 * expected.norm());
}
