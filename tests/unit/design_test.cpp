// Boier-Martin et al. §4.2-4.3: constraints propagated through the hierarchy, and the
// constrained solve (paper mode and exact KKT).
#include <catch2/catch.hpp>

#include "design/edit_solve.h"
#include "energy/local_quadratic.h"
#include "experiment/components.h"
#include "io/mesh_io.h"
#include "problem/least_squares.h"
#include "test_support.h"

using namespace fairshape;

namespace {

MultiresSurface quad_hierarchy(int levels) {
  return MultiresSurface(read_mesh(test::data_path("double-torus-example.off")), {}, levels, Backend::Optimized);
}

std::unique_ptr<Solver> cholesky() {
  Config none;
  return components().solvers.create("cholesky", Backend::Optimized, none);
}

EditProblem detail_preserving(const MultiresSurface& h, int level, const std::vector<PointConstraint>& cs) {
  EditProblem p;
  p.H = stretch_bend_hessian(h.mesh(level), {0.1, 1.0}, Backend::Optimized);
  p.g = Eigen::MatrixXd::Zero(p.H.rows(), 3);
  p.constraints = propagate_constraints(h, level, cs);
  return p;
}

}  // namespace

TEST_CASE("Table 1: the coarse-level constraint masks are the Catmull-Clark rows of S", "[design][bm]") {
  const MultiresSurface h = quad_hierarchy(2);  // level 1 is all quads
  const SurfaceMesh& m = h.mesh(1);
  const RowSparseMatrix S = h.subdivision_operator(1);
  auto weight = [&](int row, int col) { return S.coeff(row, col); };
  int checked = 0;
  for (int v = 0; v < m.n_vertices(); ++v) {
    if (m.is_boundary_vertex(v)) continue;
    const double k = m.valence(v), beta = 3.0 / (2.0 * k), gamma = 1.0 / (4.0 * k);  // Table 1, interior even
    CHECK(weight(v, v) == Approx(1.0 - beta - gamma).epsilon(1e-14));
    for (int hh : m.outgoing_halfedges(v)) {
      CHECK(weight(v, m.to_vertex(hh)) == Approx(beta / k).epsilon(1e-14));
      CHECK(weight(v, m.to_vertex(m.next(hh))) == Approx(gamma / k).epsilon(1e-14));  // the quad's diagonal
    }
    ++checked;
  }
  CHECK(checked > 100);
  const int nv = m.n_vertices(), ne = m.n_edges();
  for (int f = 0; f < m.n_faces(); ++f)  // odd face vertex: 1/4 of the four corners
    for (int v : m.face_vertices(f)) CHECK(weight(nv + ne + f, v) == Approx(0.25));
  for (int e = 0; e < ne; ++e) {  // odd edge vertex: 3/8 endpoints, 1/16 the other four
    const int a = m.from_vertex(2 * e), b = m.to_vertex(2 * e);
    CHECK(weight(nv + e, a) == Approx(3.0 / 8.0));
    CHECK(weight(nv + e, b) == Approx(3.0 / 8.0));
    CHECK(weight(nv + e, m.to_vertex(m.next(m.next(2 * e)))) == Approx(1.0 / 16.0));
  }
}

TEST_CASE("propagated rows map the edit level to the constrained level", "[design][bm]") {
  const MultiresSurface h = quad_hierarchy(2);
  std::vector<PointConstraint> cs;
  for (int v : {0, 7, 123}) cs.push_back({2, v, false, Vec3::Zero(), "c"});
  for (int l : {0, 1, 2}) {
    const LinearConstraints lc = propagate_constraints(h, l, cs);
    const MatrixX3 mapped = lc.A * h.mesh(l).positions();
    for (int r = 0; r < 3; ++r) CHECK((mapped.row(r) - h.mesh(2).positions().row(cs[r].vertex)).norm() <= 1e-12);
  }
  // Coarser edit level, wider rows: the region of influence grows (Figure 1 b vs c).
  CHECK(propagate_constraints(h, 0, cs).A.nonZeros() < propagate_constraints(h, 2, cs).A.nonZeros() * 100);
  const auto fine = propagate_constraints(h, 2, cs), coarse = propagate_constraints(h, 0, cs);
  CHECK(fine.A.nonZeros() == 3);
  CHECK(coarse.A.nonZeros() > 3);
}

TEST_CASE("both constraint modes satisfy the constraints, and agree when they are determined", "[design][bm]") {
  const MultiresSurface h = quad_hierarchy(1);
  auto solver = cholesky();
  std::vector<PointConstraint> cs{{1, 10, false, Vec3(0.1, 0.2, 0.0), "a"}, {1, 300, false, Vec3(0, 0, -0.1), "b"},
                                  {1, 500, false, Vec3::Zero(), "c"}, {1, 800, false, Vec3::Zero(), "d"}};
  const EditProblem p = detail_preserving(h, 1, cs);  // constraints on the edit level itself
  const EditSolution paper = solve_edit(p, ConstraintMode::Paper, *solver, Backend::Optimized);
  const EditSolution kkt = solve_edit(p, ConstraintMode::Kkt, *solver, Backend::Optimized);
  CHECK(paper.constraint_residual <= 1e-10);
  CHECK(kkt.constraint_residual <= 1e-10);
  CHECK((paper.delta - kkt.delta).norm() <= 1e-8 * kkt.delta.norm());
  // Propagated to the base level, paper mode still meets the (underdetermined) constraints.
  const EditProblem coarse = detail_preserving(h, 0, cs);
  CHECK(solve_edit(coarse, ConstraintMode::Paper, *solver, Backend::Optimized).constraint_residual <= 1e-10);
  CHECK(solve_edit(coarse, ConstraintMode::Kkt, *solver, Backend::Reference).constraint_residual <= 1e-10);
}

TEST_CASE("a common offset on every target gives that translation (KKT), zero offsets give nothing", "[design][bm]") {
  const MultiresSurface h = quad_hierarchy(2);
  auto solver = cholesky();
  const Vec3 t(0.3, -0.1, 0.2);
  std::vector<PointConstraint> cs;
  for (int v : {3, 90, 400, 1000}) cs.push_back({2, v, false, t, std::string("c").append(std::to_string(v))});
  const EditSolution moved = solve_edit(detail_preserving(h, 0, cs), ConstraintMode::Kkt, *solver, Backend::Optimized);
  CHECK((moved.delta.rowwise() - t.transpose()).norm() <= 1e-8);
  for (auto& c : cs) c.offset.setZero();
  for (ConstraintMode mode : {ConstraintMode::Kkt, ConstraintMode::Paper})
    CHECK(solve_edit(detail_preserving(h, 0, cs), mode, *solver, Backend::Optimized).delta.norm() <= 1e-12);
}

TEST_CASE("minimum-norm least squares: reference and optimized agree", "[design][bm][conformance]") {
  SparseMatrix A(3, 8);
  Triplets t{{0, 0, 0.5}, {0, 1, 0.25}, {0, 2, 0.25}, {1, 2, 0.5}, {1, 3, 0.5}, {2, 5, 0.75}, {2, 7, 0.25}};
  A.setFromTriplets(t.begin(), t.end());
  const Eigen::MatrixXd C = Eigen::MatrixXd::Random(3, 3);
  const auto r = min_norm_least_squares(A, C, Backend::Reference), o = min_norm_least_squares(A, C, Backend::Optimized);
  CHECK(r.residual <= 1e-12);
  CHECK((r.X - o.X).norm() <= 1e-10 * r.X.norm());
  CHECK(r.rank == 3);
}

TEST_CASE("large constraint systems stay sparse on both back ends", "[design][bm]") {
  // 20,000 fixed vertices (square, identity-like) and 5,000 rows over 20,000 vertices (wide).
  for (const auto& [m, k] : std::vector<std::pair<int, int>>{{20000, 20000}, {5000, 20000}}) {
    SparseMatrix A(m, k);
    Triplets t;
    for (int i = 0; i < m; ++i) {
      t.emplace_back(i, i, 0.75);
      t.emplace_back(i, (i + m) % k, 0.25);
    }
    A.setFromTriplets(t.begin(), t.end());
    const Eigen::MatrixXd C = Eigen::MatrixXd::Random(m, 3);
    for (Backend b : {Backend::Reference, Backend::Optimized}) {
      const auto r = min_norm_least_squares(A, C, b);
      CHECK(r.residual <= 1e-10 * C.norm());
    }
  }
}

TEST_CASE("bad constraints are refused with what is wrong", "[design][bm]") {
  const MultiresSurface h = quad_hierarchy(1);
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(propagate_constraints(h, 0, {{1, 5, false, Vec3(1, 0, 0), "nose"}, {1, 5, false, Vec3(0, 1, 0), "ear"}}),
                    Contains("vertex 5 of level 1 has incompatible targets: nose") && Contains("ear"));
  CHECK_THROWS_WITH(propagate_constraints(h, 1, {{0, 5, false, Vec3::Zero(), "c"}}),
                    Contains("coarser than the edit level 1"));
  CHECK_THROWS_WITH(propagate_constraints(h, 0, {{1, 99999, false, Vec3::Zero(), "c"}}), Contains("vertex 99999 does not exist"));
  CHECK_THROWS_WITH(propagate_constraints(h, 0, {{3, 1, false, Vec3::Zero(), "c"}}), Contains("not in the hierarchy"));
  auto solver = cholesky();
  CHECK_THROWS_WITH(solve_edit(detail_preserving(h, 0, {}), ConstraintMode::Paper, *solver, Backend::Optimized),
                    Contains("no constraint"));
}
