// Boier-Martin et al. §4.2-4.3: constraints propagated through the hierarchy, and the
// constrained solve (paper mode and exact KKT).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "fairshape/design/edit_solve.h"
#include "fairshape/design/multires_constraints.h"
#include "fairshape/energy/local_quadratic.h"
#include "fairshape/experiment/components.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/problem/least_squares.h"
#include "edit_test_support.h"
#include "test_support.h"

using namespace fairshape;

namespace {

MultiresSurface quad_hierarchy(int levels) {
  return MultiresSurface(read_mesh(test::data_path("double-torus-example.off")), {}, levels, Backend::Optimized);
}

using test::cholesky;
using test::detail_preserving;

EditProblem detail_preserving(const MultiresSurface& h, int level, const std::vector<PointConstraint>& cs) {
  return detail_preserving(h, level, DesignConstraints{cs, {}, {}});
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

TEST_CASE("Welch & Witkin's solvers serve the Catmull-Clark editor: range space equals KKT, QR-penalty is close", "[design][bm][qp]") {
  const MultiresSurface h = quad_hierarchy(1);
  auto solver = cholesky();
  std::vector<PointConstraint> cs{{1, 10, false, Vec3(0.1, 0.2, 0.0), "a"}, {1, 300, false, Vec3(0, 0, -0.1), "b"},
                                  {1, 500, false, Vec3::Zero(), "c"}, {1, 800, false, Vec3::Zero(), "d"}};
  const EditProblem p = detail_preserving(h, 0, cs);  // propagated rows, underdetermined
  const EditSolution kkt = solve_edit(p, ConstraintMode::Kkt, *solver, Backend::Optimized);
  const EditSolution range = solve_edit(p, ConstraintMode::RangeSpace, *solver, Backend::Optimized);
  REQUIRE(range.summary.termination == Termination::Converged);
  CHECK(range.constraint_residual <= 1e-8);
  CHECK((range.delta - kkt.delta).norm() <= 1e-6 * kkt.delta.norm());
  for (const Backend b : {Backend::Reference, Backend::Optimized}) {
    const EditSolution penalty = solve_edit(p, ConstraintMode::QrPenalty, *solver, b);
    REQUIRE(penalty.summary.termination == Termination::Converged);
    CHECK(penalty.constraint_residual <= 1e-4);  // default mu = 1e3, three refinement steps
    CHECK((penalty.delta - kkt.delta).norm() <= 1e-2 * kkt.delta.norm());
  }
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
  CHECK_THROWS_WITH(solve_edit(detail_preserving(h, 0, DesignConstraints{}), ConstraintMode::Paper, *solver, Backend::Optimized),
                    Contains("no constraint"));
}

TEST_CASE("validation's check of the constraints refuses what propagation and the solve refuse, alike", "[design][bm]") {
  const MultiresSurface h = quad_hierarchy(1);
  const auto point = [](int level, int v, Vec3 offset, std::string label) {
    return PointConstraint{level, v, false, offset, std::move(label)};
  };
  const auto normal = [](int level, int v, Vec3 n, std::string label) { return NormalConstraint{level, v, n, std::move(label)}; };
  const auto dc = [](std::vector<PointConstraint> p, std::vector<NormalConstraint> n) {
    return DesignConstraints{std::move(p), std::move(n), {}};
  };
  const std::vector<std::pair<std::string, DesignConstraints>> cases{
      {"valid", dc({point(1, 5, Vec3(1, 0, 0), "a"), point(1, 6, Vec3::Zero(), "b")}, {normal(1, 7, Vec3(0, 0, 1), "n")})},
      {"the same target twice", dc({point(1, 5, Vec3(1, 0, 0), "a"), point(1, 5, Vec3(1, 0, 0), "b")}, {})},
      {"the same normal twice",
       dc({point(1, 5, Vec3::Zero(), "a")}, {normal(1, 7, Vec3(0, 0, 1), "n"), normal(1, 7, Vec3(0, 0, 2), "m")})},
      {"incompatible targets", dc({point(1, 5, Vec3(1, 0, 0), "a"), point(1, 5, Vec3(0, 1, 0), "b")}, {})},
      {"opposite normals",
       dc({point(1, 5, Vec3::Zero(), "a")}, {normal(1, 7, Vec3(0, 0, 1), "n"), normal(1, 7, Vec3(0, 0, -1), "m")})},
      {"a missing vertex", dc({point(1, 99999, Vec3::Zero(), "a")}, {})},
      {"a missing level", dc({point(3, 1, Vec3::Zero(), "a")}, {})},
      {"a zero normal", dc({point(1, 5, Vec3::Zero(), "a")}, {normal(1, 7, Vec3::Zero(), "n")})},
      {"no constraint", dc({}, {})},
      {"normals alone", dc({}, {normal(1, 7, Vec3(0, 0, 1), "n")})},
  };

  for (const auto& [what, dc] : cases) {
    INFO(what);
    std::string by_check, by_propagation;
    try {
      check_constraints(h, 1, dc);
    } catch (const InvalidInput& e) {
      by_check = e.what();
    }
    try {
      require_fixed_position(propagate_constraints(h, 1, dc));
    } catch (const InvalidInput& e) {
      by_propagation = e.what();
    }
    CHECK(by_check == by_propagation);
    CHECK(by_check.empty() == (what == "valid" || what.rfind("the same", 0) == 0));
  }
  // A normal requested twice is one pair of rows, not a dependent second pair.
  CHECK(propagate_constraints(h, 1, cases[2].second).A_coupled.rows() == 2);
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(check_constraints(h, 1, cases[4].second),
                    Contains("vertex 7 of level 1 has incompatible normals: n") && Contains("m for [ 0  0 -1]"));
}

namespace {

std::unique_ptr<Solver> gauss_seidel(Backend b) {
  Config cfg(YAML::Load("{tolerance: 1.0e-12, max_iterations: 200000}"), "solver");
  return components().solvers.create("gauss_seidel", b, cfg);
}

}  // namespace

TEST_CASE("a normal constraint makes the estimated normal equal the target", "[design][bm][normal]") {
  const MultiresSurface h = quad_hierarchy(1);
  const int v = 200, level = 1;
  const SurfaceMesh& rest = h.mesh(level);
  const Vec3 n0 = estimated_normal(rest, rest.positions(), v);
  // Tilt the normal by 25 degrees about a tangent direction; pin the vertex and a far region.
  const Vec3 tangent = n0.unitOrthogonal();
  const Vec3 target = Eigen::AngleAxisd(25.0 * M_PI / 180.0, tangent) * n0;
  for (int edit : {1, 0}) {
    DesignConstraints dc;  // the far region is pinned on the edit level, where it has as many vertices as rows
    dc.normals.push_back({level, v, target, "tilt"});
    dc.points.push_back({level, v, false, Vec3::Zero(), "pin"});
    const SurfaceMesh& e = h.mesh(edit);
    for (int w = 0; w < e.n_vertices(); ++w)
      if ((e.position(w) - rest.position(v)).norm() > 2.5) dc.points.push_back({edit, w, false, Vec3::Zero(), "far"});
    const EditProblem p = detail_preserving(h, edit, dc);
    REQUIRE(p.constraints.coupled());
    Eigen::MatrixXd by_backend[2];
    for (ConstraintMode mode : {ConstraintMode::Kkt, ConstraintMode::Paper})
      for (Backend b : {Backend::Reference, Backend::Optimized}) {
        INFO("edit level " << edit << ", " << (mode == ConstraintMode::Kkt ? "kkt" : "paper") << ", " << to_string(b));
        auto solver = gauss_seidel(b);
        const EditSolution s = solve_edit(p, mode, *solver, b);
        REQUIRE(s.delta.rows() == h.mesh(edit).n_vertices());
        CHECK(s.constraint_residual <= 1e-10);
        const MatrixX3 moved = rest.positions() + MatrixX3(h.prolongation(edit, level) * s.delta);
        const Vec3 n = estimated_normal(rest, moved, v);
        CHECK(n.dot(target) >= 1.0 - 1e-10);
        CHECK(s.delta.norm() > 1e-3);  // the surface did turn
        if (mode == ConstraintMode::Kkt) by_backend[static_cast<int>(b)] = s.delta;
      }
    CHECK((by_backend[0] - by_backend[1]).norm() <= 1e-8 * by_backend[1].norm());
  }
  // Without a point constraint the position is free: refused, not a singular solve.
  DesignConstraints only_normal;
  only_normal.normals.push_back({level, v, target, "tilt"});
  auto solver = cholesky();
  CHECK_THROWS_WITH(solve_edit(detail_preserving(h, 1, only_normal), ConstraintMode::Kkt, *solver, Backend::Optimized),
                    Catch::Matchers::Contains("normal constraints fix no position"));
}

TEST_CASE("frame rows meet a normal with its own orientation where the tangent rows meet its reverse", "[design][bm][normal]") {
  const MultiresSurface h = quad_hierarchy(1);
  const int v = 200, level = 1;
  const SurfaceMesh& rest = h.mesh(level);
  NormalConstraint probe;
  probe.level = level;
  probe.vertex = v;
  const Vec3 n0 = achieved_normal(rest, rest.positions(), probe);
  // 170 degrees from the rest normal: its tangent plane is the plane of a 10-degree tilt, which
  // the energy prefers, so §4.2's two rows are met by the reverse of the target.
  const Vec3 target = Eigen::AngleAxisd(170.0 * M_PI / 180.0, n0.unitOrthogonal()) * n0;
  const auto edit_with = [&](NormalRows rows, const MultiresSurface* current) {
    DesignConstraints dc;
    dc.normals.push_back({level, v, target, "turn", {}, rows});
    dc.points.push_back({level, v, false, Vec3::Zero(), "pin"});
    for (int w = 0; w < rest.n_vertices(); ++w)
      if ((rest.position(w) - rest.position(v)).norm() > 2.5) dc.points.push_back({level, w, false, Vec3::Zero(), "far"});
    return std::make_pair(dc, propagate_constraints(h, level, dc, current));
  };
  auto solver = cholesky();
  for (NormalRows rows : {NormalRows::Tangent, NormalRows::Frame})
    for (ConstraintMode mode : {ConstraintMode::Kkt, ConstraintMode::Paper}) {
      INFO((rows == NormalRows::Frame ? "frame" : "tangent") << ", " << (mode == ConstraintMode::Kkt ? "kkt" : "paper"));
      const auto [dc, lc] = edit_with(rows, nullptr);
      CHECK(lc.coupled() == (rows == NormalRows::Tangent));  // frame rows are rows of the point kind
      EditProblem p = detail_preserving(h, level, dc);
      const EditSolution s = solve_edit(p, mode, *solver, Backend::Optimized);
      CHECK(s.constraint_residual <= 1e-9);
      const MatrixX3 moved = rest.positions() + MatrixX3(s.delta);
      const double cosine = achieved_normal(rest, moved, dc.normals.front()).dot(target);
      if (rows == NormalRows::Tangent) CHECK(cosine < 0);  // the rows hold, the normal is reversed
      else CHECK(cosine >= 1.0 - 1e-9);
      if (rows == NormalRows::Frame && mode == ConstraintMode::Kkt) {
        // A later pass asks for what is still missing: nothing once the edit is made, the whole
        // frame turn from the rest shape — the same targets missing_targets gives.
        MultiresSurface edited = h;
        edited.set_level_positions(level, moved);
        const LinearConstraints after = edit_with(rows, &edited).second;
        CHECK(after.C.norm() <= 1e-9 * (1 + lc.C.norm()));
        const LinearConstraints missing = missing_targets(h, dc, edited);
        REQUIRE(missing.C.rows() == after.C.rows());
        CHECK((missing.C - after.C).norm() <= 1e-12 * (1 + lc.C.norm()));
        CHECK((missing_targets(h, dc, h).C - lc.C).norm() <= 1e-12 * (1 + lc.C.norm()));
      }
    }
}

TEST_CASE("a curve between vertex rows is snapped on the first finer level where it has no gap", "[design][bm][curve]") {
  const MultiresSurface h(test::grid(4), {}, 2, Backend::Optimized);  // spacing 0.25, 0.125, 0.0625
  const LevelMeshes mesh_at = [&h](int l) -> const SurfaceMesh& { return h.mesh(l); };
  Config cfg(YAML::Load("{points: [[0.3, 0.375, 0], [0.7, 0.375, 0]], translation: [0, 0, 0.1]}"), "constraints[0]");
  auto curve = components().constraints.create("curve", Backend::Optimized, cfg);
  DesignConstraints dc;
  curve->add_to(mesh_at, 2, dc);
  REQUIRE(!dc.points.empty());
  for (const auto& c : dc.points) {
    CHECK(c.level == 1);  // level 0 has no vertex near y = 0.375, level 1 has a row on it
    CHECK(std::abs(h.mesh(1).position(c.vertex).y() - 0.375) <= 1e-12);
  }
  // The surface follows: the boundary stays, the snapped vertices reach the lifted curve.
  const auto rims = h.mesh(1).boundary_loops();
  DesignConstraints with_rim = dc;
  for (int w : rims.front()) with_rim.points.push_back({1, w, false, Vec3::Zero(), "rim"});
  auto solver = cholesky();
  const EditSolution s = solve_edit(detail_preserving(h, 1, with_rim), ConstraintMode::Kkt, *solver, Backend::Optimized);
  CHECK(s.constraint_residual <= 1e-10);
  for (const auto& c : dc.points) CHECK(s.delta(c.vertex, 2) == Approx(0.1).margin(1e-10));
  // On the base level the 4 × 4 grid cannot carry these rows independently (A has rank 19 of
  // 20) and the dropped row disagrees with the kept ones: KKT fits all of them in the
  // least-squares sense and says the constraints are not met; paper mode gives its
  // least-squares answer.
  const auto base_rims = h.mesh(0).boundary_loops();
  for (int w : base_rims.front()) dc.points.push_back({0, w, false, Vec3::Zero(), "rim"});
  const EditProblem coarse = detail_preserving(h, 0, dc);
  for (Backend b : {Backend::Reference, Backend::Optimized}) {
    const EditSolution kkt = solve_edit(coarse, ConstraintMode::Kkt, *solver, b);
    INFO(kkt.summary.message);
    CHECK(kkt.summary.termination == Termination::ConstraintsUnmet);
    CHECK_THAT(kkt.summary.message, Catch::Matchers::Contains("dropped 1 dependent constraint rows"));
    CHECK(kkt.delta.allFinite());
  }
  const EditSolution paper = solve_edit(coarse, ConstraintMode::Paper, *solver, Backend::Optimized);
  CHECK(paper.delta.allFinite());
  CHECK(paper.constraint_residual < coarse.constraints.C.norm());
}

TEST_CASE("rotating an annulus' inner rim: constraints met, the result keeps the annulus' symmetry", "[design][bm][curve]") {
  const MultiresSurface h(read_mesh(test::data_path("annulus.obj")), {}, 2, Backend::Optimized);
  const LevelMeshes mesh_at = [&h](int l) -> const SurfaceMesh& { return h.mesh(l); };
  const SurfaceMesh& fine = h.mesh(2);
  const Eigen::Matrix3d twist = Eigen::AngleAxisd(M_PI / 3, Vec3::UnitZ()).toRotationMatrix();
  const Vec3 lift(0, 0, 0.3);
  auto solver = cholesky();
  for (int edit : {0, 2}) {
    INFO("edit level " << edit);
    DesignConstraints dc;  // the rims of the edit level: inner turned 60° and lifted, outer fixed
    const std::string level = std::to_string(edit);
    for (const std::string& yaml : {"{boundary_loop_near: [0, 0, 0], rotation: {axis: [0, 0, 1], angle_deg: 60}, "
                                   "translation: [0, 0, 0.3], level: " + level + "}",
                                   "{boundary_loop_near: [1, 0, 0], level: " + level + "}"}) {
      Config cfg(YAML::Load(yaml), "constraints[0]");
      components().constraints.create("rigid", Backend::Optimized, cfg)->add_to(mesh_at, 2, dc);
    }
    const EditSolution s = solve_edit(detail_preserving(h, edit, dc), ConstraintMode::Kkt, *solver, Backend::Optimized);
    CHECK(s.constraint_residual <= 1e-10);
    const Eigen::MatrixXd d = h.prolongation(edit, 2) * s.delta;
    // Boundary rules use boundary vertices only, so the fine inner rim turns rigidly too.
    const auto rims = fine.boundary_loops();
    for (const auto& rim : rims)
      for (int v : rim) {
        const Vec3 p = fine.position(v);
        if (p.norm() > 0.7) continue;  // the outer rim
        CHECK((p + Vec3(d.row(v).transpose()) - (twist * p + lift)).norm() <= 1e-10);
      }
    // 16-fold symmetry: a vertex and its copy turned by 2π/16 move alike (|Δ| and Δz).
    int compared = 0;
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(2 * M_PI / 16, Vec3::UnitZ()).toRotationMatrix();
    for (int a = 0; a < fine.n_vertices(); a += 7) {
      const Vec3 q = turn * fine.position(a);
      Eigen::Index b = 0;
      if ((fine.positions().rowwise() - q.transpose()).rowwise().norm().minCoeff(&b) > 1e-9) continue;
      CHECK(std::abs(d.row(a).norm() - d.row(b).norm()) <= 1e-8);
      CHECK(std::abs(d(a, 2) - d(b, 2)) <= 1e-8);
      ++compared;
    }
    CHECK(compared > 50);
  }
}

TEST_CASE("rank-deficient constraint systems: the sparse path gives A⁺C on both back ends", "[design][bm][conformance]") {
  // Rows of a propagated operator and sums of them: wide and tall, consistent or not.
  const MultiresSurface h = quad_hierarchy(1);
  const RowSparseMatrix P = h.prolongation(0, 1);
  for (const auto& [rows, consistent] : std::vector<std::pair<int, bool>>{{150, true}, {150, false}, {900, true}}) {
    Triplets t;  // two thirds rows of P, then sums of two of those (dependent by construction)
    const int base = 2 * rows / 3;
    auto copy_row = [&](int r, int src) {
      for (RowSparseMatrix::InnerIterator it(P, src); it; ++it) t.emplace_back(r, static_cast<int>(it.col()), it.value());
    };
    for (int r = 0; r < base; ++r) copy_row(r, r);
    for (int r = base; r < rows; ++r) {
      copy_row(r, r - base);
      copy_row(r, r - base + 1);
    }
    SparseMatrix A(rows, P.cols());
    A.setFromTriplets(t.begin(), t.end());
    const Eigen::MatrixXd X0 = Eigen::MatrixXd::Random(P.cols(), 3);
    Eigen::MatrixXd C = A * X0;
    if (!consistent) C += 0.1 * Eigen::MatrixXd::Random(rows, 3);
    const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod{Eigen::MatrixXd(A)};
    const Eigen::MatrixXd exact = cod.solve(C);
    INFO(rows << " rows, rank " << cod.rank() << (consistent ? ", consistent" : ", inconsistent"));
    REQUIRE(cod.rank() < rows);  // dependent rows
    for (Backend b : {Backend::Reference, Backend::Optimized}) {
      const auto r = min_norm_least_squares(A, C, b);
      CHECK(r.rank == cod.rank());
      CHECK((r.X - exact).norm() <= 1e-8 * exact.norm());
    }
  }
}
