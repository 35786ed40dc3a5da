#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <cstdlib>

#include "fairshape/io/json_io.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/subdivision/multires_surface.h"
#include "fairshape/subdivision/subdivider.h"
#include "test_support.h"

using namespace fairshape;

namespace {

struct Case {
  const char* file;
  SubdivisionOptions opt;
};
std::vector<Case> cases() {
  return {{"mushroom.off", {SchemeType::Loop, BoundaryMode::EdgeOnly, LoopWeights::Loop}},
          {"mushroom.off", {SchemeType::CatmullClark, BoundaryMode::EdgeAndCorner, LoopWeights::Loop}},
          {"double-torus-example.off", {SchemeType::CatmullClark, BoundaryMode::EdgeOnly, LoopWeights::Loop}}};
}

// The finest level of a 2-level hierarchy with random details: a fine semi-regular mesh.
MatrixX3 detailed_fine(const SurfaceMesh& base, const SubdivisionOptions& opt, double amplitude) {
  MultiresSurface h(base, opt, 2, Backend::Optimized);
  const double size = (base.positions().colwise().maxCoeff() - base.positions().colwise().minCoeff()).norm();
  for (int l = 1; l <= 2; ++l)
    h.set_details(l, amplitude * size * MatrixX3::Random(h.mesh(l).n_vertices(), 3), DetailSpace::World);
  h.synthesize(DetailSpace::World);
  return h.mesh(2).positions();
}

double rel(const MatrixX3& a, const MatrixX3& b) { return (a - b).norm() / b.norm(); }

}  // namespace

TEST_CASE("analysis then synthesis reproduces a fine mesh, world and local details", "[multires]") {
  for (const auto& c : cases()) {
    INFO(c.file << " " << to_string(c.opt.scheme));
    const SurfaceMesh base = read_mesh(test::data_path(c.file));
    const MatrixX3 fine = detailed_fine(base, c.opt, 0.01);
    for (DetailSpace keep : {DetailSpace::World, DetailSpace::Local}) {
      MultiresSurface h = MultiresSurface::analyze(base, fine, c.opt, 2, Backend::Optimized);
      h.synthesize(keep);
      CHECK(rel(h.mesh(2).positions(), fine) <= 1e-12);
    }
  }
}

TEST_CASE("a pure subdivision surface analyses to its base with zero details", "[multires]") {
  for (const auto& c : cases()) {
    const SurfaceMesh base = read_mesh(test::data_path(c.file));
    const MultiresSurface smooth(base, c.opt, 2, Backend::Reference);
    const MultiresSurface h = MultiresSurface::analyze(base, smooth.mesh(2).positions(), c.opt, 2, Backend::Reference);
    CHECK(rel(h.mesh(0).positions(), base.positions()) <= 1e-10);
    for (int l = 1; l <= 2; ++l) CHECK(h.details(l, DetailSpace::World).norm() <= 1e-10 * base.positions().norm());
  }
}

TEST_CASE("local details follow a rigid motion of the base, world details do not", "[multires]") {
  const SurfaceMesh base = read_mesh(test::data_path("mushroom.off"));
  const SubdivisionOptions opt{SchemeType::Loop, BoundaryMode::EdgeOnly, LoopWeights::Loop};
  const MatrixX3 fine = detailed_fine(base, opt, 0.01);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::RowVector3d t(0.3, -0.2, 1.0);
  const MatrixX3 moved_fine = (fine * R.transpose()).rowwise() + t;
  for (DetailSpace keep : {DetailSpace::Local, DetailSpace::World}) {
    MultiresSurface h = MultiresSurface::analyze(base, fine, opt, 2, Backend::Optimized);
    h.set_base_positions((h.mesh(0).positions() * R.transpose()).rowwise() + t);
    h.synthesize(keep);
    if (keep == DetailSpace::Local) CHECK(rel(h.mesh(2).positions(), moved_fine) <= 1e-10);
    else CHECK(rel(h.mesh(2).positions(), moved_fine) > 1e-4);
  }
}

TEST_CASE("reference and optimized hierarchies agree", "[multires][conformance]") {
  const SurfaceMesh base = read_mesh(test::data_path("double-torus-example.off"));
  const SubdivisionOptions opt;
  const MatrixX3 fine = detailed_fine(base, opt, 0.02);
  const auto a = MultiresSurface::analyze(base, fine, opt, 2, Backend::Reference);
  const auto b = MultiresSurface::analyze(base, fine, opt, 2, Backend::Optimized);
  CHECK(rel(a.mesh(0).positions(), b.mesh(0).positions()) <= 1e-12);
  for (int l = 1; l <= 2; ++l)
    CHECK((a.details(l, DetailSpace::Local) - b.details(l, DetailSpace::Local)).norm() <=
          1e-12 * (1.0 + a.details(l, DetailSpace::Local).norm()));
}

TEST_CASE("hierarchies round-trip through .vtm, and inconsistent files are refused", "[multires][io]") {
  const auto dir = test::scratch_dir("multires_io");
  const SurfaceMesh base = read_mesh(test::data_path("double-torus-example.off"));
  const SubdivisionOptions opt{SchemeType::CatmullClark, BoundaryMode::EdgeAndCorner, LoopWeights::Loop};
  const auto h = MultiresSurface::analyze(base, detailed_fine(base, opt, 0.02), opt, 2, Backend::Optimized);
  h.save((dir / "h.vtm").string());
  const auto back = MultiresSurface::load((dir / "h.vtm").string(), Backend::Optimized);
  CHECK(back.levels() == 2);
  CHECK(back.options().boundary == BoundaryMode::EdgeAndCorner);
  CHECK(rel(back.mesh(2).positions(), h.mesh(2).positions()) <= 1e-12);
  CHECK(rel(back.details(2, DetailSpace::Local), h.details(2, DetailSpace::Local)) <= 1e-10);
  // An open grid saved with pinned corners, then claimed to use edge-only rules: the stored
  // levels no longer match base + details.
  const SurfaceMesh grid = test::grid(3);
  MultiresSurface(grid, opt, 2, Backend::Optimized).save((dir / "h.vtm").string());
  write_json({{"format", "fairshape multiresolution surface"}, {"scheme", "catmull-clark"}, {"boundary", "edge-only"},
              {"weights", "loop"}, {"levels", 2}},
             (dir / "h.json").string());
  CHECK_THROWS_WITH(MultiresSurface::load((dir / "h.vtm").string(), Backend::Optimized),
                    Catch::Matchers::Contains("does not match base + details"));
  CHECK_THROWS_AS(MultiresSurface::analyze(base, MatrixX3::Zero(5, 3), opt, 2, Backend::Optimized), InvalidInput);
}

TEST_CASE("a synthesis restricted to what a change reaches equals the whole synthesis", "[multires]") {
  // The helmet's Loop hierarchy with random details (both representations kept in turn); three
  // base vertices moved, or one vertex of level 1: the region synthesis against synthesize_from.
  SubdivisionOptions loop;
  loop.scheme = SchemeType::Loop;
  const SurfaceMesh base = read_mesh(test::data_path("helmet.off"));
  for (const DetailSpace keep : {DetailSpace::Local, DetailSpace::World}) {
    for (const int level : {0, 1}) {
      INFO((keep == DetailSpace::Local ? "local" : "world") << " details, change on level " << level);
      MultiresSurface h(base, loop, 3, Backend::Optimized);
      std::srand(11);
      for (int k = 1; k <= 3; ++k) h.set_details(k, 2e-3 * MatrixX3::Random(h.mesh(k).n_vertices(), 3), keep);
      h.synthesize(keep);
      const MultiresSurface before = h;
      const std::vector<int> changed{5, 17, 300};
      MatrixX3 X = h.mesh(level).positions();
      for (int v : changed) X.row(v) += Vec3(0.01, -0.02, 0.015).transpose();
      h.set_level_positions(level, X);
      MultiresSurface whole = h;
      whole.synthesize_from(level, keep);
      const std::vector<std::vector<int>> region = h.synthesize_region_from(level, changed, keep);
      REQUIRE(region.size() == 4);
      for (int k = level + 1; k <= 3; ++k) {
        INFO("level " << k);
        CHECK((h.mesh(k).positions() - whole.mesh(k).positions()).cwiseAbs().maxCoeff() <= 1e-12);
        const DetailSpace other = keep == DetailSpace::Local ? DetailSpace::World : DetailSpace::Local;
        CHECK((h.details(k, other) - whole.details(k, other)).cwiseAbs().maxCoeff() <= 1e-12);
        std::vector<char> in(static_cast<std::size_t>(h.mesh(k).n_vertices()), 0);
        for (int v : region[static_cast<std::size_t>(k)]) in[static_cast<std::size_t>(v)] = 1;
        int touched_outside = 0;
        for (int v = 0; v < h.mesh(k).n_vertices(); ++v)
          touched_outside += !in[static_cast<std::size_t>(v)] &&
                             (h.mesh(k).positions().row(v).array() != before.mesh(k).positions().row(v).array()).any();
        CHECK(touched_outside == 0);
        // Local: a part of the level (a stencil and a ring per level; three of the helmet's 500
        // base vertices reach about a fifth of the finer levels, one of level 1 a few percent).
        CHECK(region[static_cast<std::size_t>(k)].size() < static_cast<std::size_t>(h.mesh(k).n_vertices()) / (level == 0 ? 3 : 10));
      }
    }
  }
}

TEST_CASE("the detail fit is the least-squares one: its residual is orthogonal to every coarse basis function",
          "[multires]") {
  // Normal equations Sᵀ(X − S c) = 0 on each level: the optimized back end iterates (CG on
  // SᵀS), the reference factors SᵀS; both must reach the factorization's accuracy.
  for (const auto& c : cases()) {
    INFO(c.file << " " << to_string(c.opt.scheme));
    const SurfaceMesh base = read_mesh(test::data_path(c.file));
    const MatrixX3 fine = detailed_fine(base, c.opt, 0.05);
    for (Backend b : {Backend::Reference, Backend::Optimized}) {
      const MultiresSurface h = MultiresSurface::analyze(base, fine, c.opt, 2, b);
      for (int l = 0; l < 2; ++l) {
        const SparseMatrix& S = h.subdivision_operator(l);
        const MatrixX3 finer = h.mesh(l + 1).positions();
        const MatrixX3 normal = S.transpose() * (finer - S * h.mesh(l).positions());
        CHECK(normal.norm() <= 1e-12 * MatrixX3(S.transpose() * finer).norm());
      }
    }
  }
}
