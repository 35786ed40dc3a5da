// Boier-Martin et al. §3.3-3.4: divided differences from local quadratic fits, and the
// stretch + bend matrix H built from them.
#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>

#include "fairshape/energy/divided_differences.h"
#include "fairshape/energy/local_quadratic.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/subdivision/subdivider.h"
#include "test_support.h"

using namespace fairshape;

namespace {
// z = f(x, y), a quadratic, sampled on a flat regular grid of spacing h.
double f(double x, double y) { return 0.3 + 0.7 * x - 1.1 * y + 0.5 * 2.0 * x * x + 1.5 * x * y + 0.5 * -3.0 * y * y; }
}  // namespace

TEST_CASE("ordered one-rings: edge and face neighbours in angular order", "[energy][bm]") {
  const SurfaceMesh g = test::grid(4);  // 5 x 5 vertices
  const auto interior = ordered_one_ring(g, 6);  // (1, 1): 4 edge + 4 face neighbours
  CHECK(interior.size() == 8);
  const auto corner = ordered_one_ring(g, 0);  // one face: 2 edge + 1 face neighbour
  CHECK(corner.size() == 3);
  const auto side = ordered_one_ring(g, 2);  // boundary: 3 edge + 2 face neighbours, from one boundary neighbour
  REQUIRE(side.size() == 5);
  CHECK(((side.front() == 1 && side.back() == 3) || (side.front() == 3 && side.back() == 1)));
  // Consecutive ring members are angularly adjacent: each step turns by 45 degrees on the grid.
  const Eigen::MatrixX2d uv = polar_map(g, 6, interior);
  for (int j = 0; j < 8; ++j) {
    const double a0 = std::atan2(uv(j, 1), uv(j, 0)), a1 = std::atan2(uv((j + 1) % 8, 1), uv((j + 1) % 8, 0));
    CHECK(std::remainder(a1 - a0, 2 * M_PI) == Approx(M_PI / 4));
  }
}

TEST_CASE("divided differences reproduce the derivatives of a quadratic exactly", "[energy][bm]") {
  const SurfaceMesh g = test::grid(6);  // spacing 1/6: the polar map of an interior vertex is the grid itself
  for (int v : {8, 16, 24}) {
    const LocalFit fit = local_fit(g, v);
    const double x0 = g.positions()(v, 0), y0 = g.positions()(v, 1);
    Eigen::VectorXd dz(fit.ring.size());
    for (std::size_t j = 0; j < fit.ring.size(); ++j)
      dz[j] = f(g.positions()(fit.ring[j], 0), g.positions()(fit.ring[j], 1)) - f(x0, y0);
    const Eigen::VectorXd d = fit.D * dz;  // (Q_u, Q_v, Q_uu, Q_uv, Q_vv)
    // The polar map starts at the first ring neighbour: rotate the known gradient into it.
    const Eigen::MatrixX2d uv = polar_map(g, v, fit.ring);
    const Vec3 first = g.position(fit.ring[0]) - g.position(v);
    const double phi = std::atan2(first.y(), first.x()) - std::atan2(uv(0, 1), uv(0, 0));
    const double c = std::cos(phi), s = std::sin(phi);
    const double fx = 0.7 + 2.0 * x0 + 1.5 * y0, fy = -1.1 + 1.5 * x0 - 3.0 * y0;
    CHECK(d[0] == Approx(c * fx + s * fy).margin(1e-10));
    CHECK(d[1] == Approx(-s * fx + c * fy).margin(1e-10));
    // Laplacian and the Hessian's invariants do not depend on the rotation.
    CHECK(d[2] + d[4] == Approx(2.0 - 3.0).margin(1e-9));
    CHECK(d[2] * d[4] - d[3] * d[3] == Approx(2.0 * -3.0 - 1.5 * 1.5).margin(1e-8));
  }
}

TEST_CASE("rank-deficient fits: full-rank case unchanged, slope exact, curvature least norm", "[energy][bm]") {
  const SurfaceMesh g = test::grid(3);
  const LocalFit corner = local_fit(g, 0);  // three neighbours
  CHECK(corner.D.rows() == 5);
  CHECK(corner.D.cols() == 3);
  CHECK(corner.D.allFinite());
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Random(8, 5);  // full rank: the paper's formula
  const Eigen::MatrixXd paper = (Phi.transpose() * Phi).inverse() * Phi.transpose();
  CHECK((least_squares_operator(Phi) - paper).norm() <= 1e-10 * paper.norm());
}

TEST_CASE("H is symmetric PSD, constants in its null space, bend kills affine maps of a flat mesh", "[energy][bm]") {
  const SurfaceMesh closed = refine_uniform(read_mesh(test::data_path("torus_quad.off")), {}, 1, Backend::Optimized).back();
  const SparseMatrix H = stretch_bend_hessian(closed, {0.1, 1.0}, Backend::Reference);
  CHECK((SparseMatrix(H.transpose()) - H).norm() <= 1e-12 * H.norm());
  CHECK((H * Eigen::VectorXd::Ones(H.rows())).norm() <= 1e-10 * H.norm());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig{Eigen::MatrixXd(H)};
  CHECK(eig.eigenvalues().minCoeff() >= -1e-10 * eig.eigenvalues().maxCoeff());

  // On a flat sheet an affine deformation has zero bending energy at every vertex: interior,
  // boundary sides (rank-deficient fits) and one-face corners (three neighbours).
  const SurfaceMesh flat = test::grid(5);
  const Eigen::VectorXd affine =
      2.0 * flat.positions().col(0) - 0.5 * flat.positions().col(1) + Eigen::VectorXd::Ones(flat.n_vertices());
  int checked = 0;
  for (int v = 0; v < flat.n_vertices(); ++v) {
    Triplets t;
    add_vertex_block(flat, v, {0.0, 1.0}, 1.0, t);
    SparseMatrix Bv(flat.n_vertices(), flat.n_vertices());
    Bv.setFromTriplets(t.begin(), t.end());
    CHECK((Bv * affine).norm() <= 1e-9 * (1.0 + Bv.norm()));
    ++checked;
  }
  CHECK(checked == flat.n_vertices());
  const SparseMatrix B = stretch_bend_hessian(flat, {0.0, 1.0}, Backend::Optimized);
  CHECK(affine.dot(B * affine) <= 1e-12 * B.norm() * affine.squaredNorm());
}

TEST_CASE("reference and optimized H agree to 1e-10", "[energy][bm][conformance]") {
  for (const char* file : {"cow.off", "mushroom.off", "double-torus-example.off"}) {
    const SurfaceMesh m = read_mesh(test::data_path(file));
    const SparseMatrix a = stretch_bend_hessian(m, {0.3, 1.0}, Backend::Reference);
    const SparseMatrix b = stretch_bend_hessian(m, {0.3, 1.0}, Backend::Optimized);
    CHECK((a - b).norm() <= 1e-10 * a.norm());
  }
}

TEST_CASE("degenerate one-rings are refused with the vertex named", "[energy][bm]") {
  MatrixX3 V = test::grid(2).positions();
  V.row(4) = V.row(1);  // the centre vertex on top of a neighbour
  const SurfaceMesh m = SurfaceMesh::from_polygons(V, test::grid(2).polygons());
  CHECK_THROWS_WITH(local_fit(m, 4), Catch::Matchers::Contains("vertex 4 coincides with its neighbour 1"));
  CHECK_THROWS_AS(stretch_bend_hessian(m, {}, Backend::Optimized), InvalidInput);
}
