// Issue 25 parts 3 and 4: edits of Sauvage, Hahmann and Bonneau's loop that stay local (the
// local explicit step and the support-restricted solve) and details in local frames.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <algorithm>

#include "fairshape/core/config.h"
#include "fairshape/curve_design/curve_metrics.h"
#include "fairshape/curve_design/detail_frames.h"
#include "fairshape/curve_design/edit_support.h"
#include "fairshape/curve_design/editing_loop.h"
#include "fairshape/curves/multires_polyline.h"
#include "fairshape/io/mesh_io.h"

using namespace fairshape;

namespace {

Polyline bundled(const std::string& name) { return read_polyline(std::string(FAIRSHAPE_SOURCE_DIR) + "/data/curves/" + name); }

std::unique_ptr<LengthSolver> trust_region() {
  Config c(YAML::Load("{length_tolerance: 1e-12, max_solves: 2000}"), "solver");
  return curve_components().solvers.create("trust_region", Backend::Optimized, c);
}

struct Recipe {
  std::unique_ptr<CurveEnergy> bending;
  std::unique_ptr<CurveConstraintKind> lengths;
  CurveObjective objective;
  explicit Recipe(double beta) {
    Config none;
    bending = curve_components().energies.create("bending", Backend::Optimized, none);
    lengths = curve_components().constraints.create("segment_lengths", Backend::Optimized, none);
    objective.smoothness = bending.get();
    objective.beta = beta;
    objective.constraints.push_back(lengths.get());
  }
};

CurveMove by(int index, Vec3 offset) {
  CurveMove m;
  m.index = index;
  m.offset = offset;
  return m;
}

CurveEdit make_edit(int e, int w, std::vector<CurveMove> moves, EditingOptions o = {}) {
  CurveEdit edit;
  edit.edit_level = e;
  edit.wrinkle_level = w;
  edit.moves = std::move(moves);
  edit.options = o;
  return edit;
}

// Largest move of a point outside the edit's support, in units of the rounding tolerance.
double outside_move(const MatrixX3& before, const MatrixX3& after, const std::vector<char>& support) {
  double worst = 0;
  for (Eigen::Index i = 0; i < before.rows(); ++i)
    if (!support[static_cast<std::size_t>(i)]) worst = std::max(worst, (after.row(i) - before.row(i)).norm());
  return worst;
}

int outside_count(const std::vector<char>& support) { return static_cast<int>(std::count(support.begin(), support.end(), 0)); }

void check_local(const EditStages& s, const char* what) {
  INFO(what << ": " << s.solve.summary.message);
  const double tol = rounding_tolerance(s.reference);
  CHECK(outside_count(s.support) > 0);
  CHECK(outside_move(s.reference, s.attracting, s.support) <= tol);
  CHECK(outside_move(s.reference, s.final, s.support) <= tol);
  REQUIRE(s.solve.converged());
  CHECK(measure_curve(s.final, false, segment_lengths(s.reference, false), s.attracting).length_error_max <= 1e-11);
}

EditingOptions sweep_whole() {
  EditingOptions o;
  o.explicit_step = ExplicitStep::Sweep;  // the loop before the edit was made local
  o.details = DetailFrames::Global;
  o.solve_region = SolveRegion::Curve;
  return o;
}

}  // namespace

TEST_CASE("local explicit step: Figure 3's edit leaves the unedited part in place", "[curve][explicit_local]") {
  const Polyline wave = bundled("wave129.obj");
  const Recipe recipe(0.01);
  const auto solver = trust_region();
  const std::vector<CurveMove> pinch{by(3, Vec3(-0.06, 0.03, 0)), by(4, Vec3(-0.3, 0, 0))};
  const EditStages local = run_editing_loop(wave, 7, make_edit(2, 3, pinch), recipe.objective, *solver, Backend::Optimized);
  check_local(local, "local");
  // The paper's whole-curve solve reshapes the unedited part (the reason for solve_region).
  const EditStages whole = run_editing_loop(wave, 7, make_edit(2, 3, pinch, sweep_whole()), recipe.objective, *solver, Backend::Optimized);
  CHECK(outside_move(whole.reference, whole.final, whole.support) > 1e-4);
}

TEST_CASE("local explicit step: Figure 4's second edit stays local, the sweep pulled the rest like a rope",
          "[curve][explicit_local]") {
  const Polyline wave = bundled("wave129.obj");
  const Recipe recipe(0.01);
  const auto solver = trust_region();
  CurveMove end;
  end.index = -1;
  end.chord_scale = 0.75;
  const EditStages first = run_editing_loop(wave, 7, make_edit(0, 1, {end}), recipe.objective, *solver, Backend::Optimized);
  REQUIRE(first.solve.converged());
  CHECK(first.support[0] == 0);  // the undragged end is outside the support of the last control point
  CHECK((first.final.row(0) - wave.points.row(0)).norm() <= rounding_tolerance(wave.points));
  const Polyline middle{first.final, false};
  const std::vector<CurveMove> push{by(5, Vec3(0.05, 0, 0)), by(6, Vec3(-0.05, 0, 0))};
  const EditStages local = run_editing_loop(middle, 7, make_edit(3, 6, push), recipe.objective, *solver, Backend::Optimized);
  check_local(local, "local");
  CHECK(outside_count(local.support) == 82);  // 129 points, the support strictly between fine points 64 and 112
  // This edit stretches its two neighbouring level-3 segments beyond their length: the moved
  // points are pulled back (said in runs.csv), nothing outside moves.
  CHECK(local.explicit_step.unreachable_chains == 0);
  CHECK(local.explicit_step.worst_pull_back > 1e-3);
  const EditStages sweep = run_editing_loop(middle, 7, make_edit(3, 6, push, sweep_whole()), recipe.objective, *solver, Backend::Optimized);
  CHECK(outside_move(sweep.reference, sweep.attracting, sweep.support) > 1e-3);
}

TEST_CASE("local explicit step: an over-stretched drag keeps the undragged end and says it could not keep the lengths",
          "[curve][explicit_local]") {
  const Polyline wave = bundled("wave129.obj");
  const Recipe recipe(0.01);
  const auto solver = trust_region();
  CurveMove end;
  end.index = -1;
  end.chord_scale = 1.6;  // beyond the curve's length
  const EditStages local = run_editing_loop(wave, 7, make_edit(0, 3, {end}), recipe.objective, *solver, Backend::Optimized);
  check_local(local, "local");
  CHECK((local.attracting.row(0) - wave.points.row(0)).norm() == 0);
  CHECK(local.explicit_step.unreachable_chains == 0);
  CHECK(local.explicit_step.worst_pull_back > 0.1);  // the drag could not be honoured: said
  // The level-(w+1) polygon of C_A has the reference lengths (a straight chain at full length).
  CHECK(local.explicit_step.moved_midpoints > 0);
  const EditStages sweep = run_editing_loop(wave, 7, make_edit(0, 3, {end}, sweep_whole()), recipe.objective, *solver, Backend::Optimized);
  CHECK((sweep.attracting.row(0) - wave.points.row(0)).norm() > 0.5);  // the old rope moved the undragged end
}

TEST_CASE("local explicit step: a stretched closed circle is fixed inside the support", "[curve][explicit_local]") {
  const Polyline ring = bundled("ring128.obj");
  const Recipe recipe(0.01);
  const auto solver = trust_region();
  SECTION("one control point slid along the ring: one side stretched, fixed locally") {
    // Level 1 of the 5-level ring has 8 control points; point 2 sits at fine point 32, (0, 1, ·).
    const CurveEdit edit = make_edit(1, 3, {by(2, Vec3(-0.02, 0, 0))});
    const EditStages s = run_editing_loop(ring, 5, edit, recipe.objective, *solver, Backend::Optimized);
    INFO(s.solve.summary.message);
    CHECK(s.explicit_step.shortened_segments > 0);
    CHECK(s.explicit_step.unreachable_chains == 0);
    const double tol = rounding_tolerance(s.reference);
    CHECK(outside_count(s.support) > 64);
    CHECK(outside_move(s.reference, s.attracting, s.support) <= tol);
    CHECK(outside_move(s.reference, s.final, s.support) <= tol);
    REQUIRE(s.solve.converged());
    CHECK(measure_curve(s.final, true, segment_lengths(s.reference, true), s.attracting).length_error_max <= 1e-11);
  }
  SECTION("all four coarse points pushed out by half the radius: pulled back until the chains reach") {
    std::vector<CurveMove> out;
    for (int k = 0; k < 4; ++k) {
      const Eigen::RowVector3d c = ring.points.row(32 * k);
      out.push_back(by(k, 0.5 * Vec3(c[0], c[1], 0)));
    }
    const Eigen::VectorXd l = segment_lengths(ring.points, true);
    const EditStages local = run_editing_loop(ring, 5, make_edit(0, 2, out), recipe.objective, *solver, Backend::Optimized);
    const EditStages sweep = run_editing_loop(ring, 5, make_edit(0, 2, out, sweep_whole()), recipe.objective, *solver, Backend::Optimized);
    CHECK(local.explicit_step.unreachable_chains == 0);
    CHECK(local.explicit_step.worst_pull_back > 0.1);
    const double local_error = measure_curve(local.attracting, true, l, local.attracting).length_error_max;
    const double sweep_error = measure_curve(sweep.attracting, true, l, sweep.attracting).length_error_max;
    INFO("attracting curve's worst segment: local " << local_error << ", sweep " << sweep_error);
    CHECK(local_error < 1.0);
    CHECK(sweep_error > 5.0);  // the segment where the sweep's two ropes met
    REQUIRE(local.solve.converged());
    CHECK(measure_curve(local.final, true, l, local.attracting).length_error_max <= 1e-11);
  }
}

namespace {

// Every level's details in the frames of their coarse segments, and back.
std::vector<MatrixX3> frame_details(const Polyline& c, int levels) {
  const PolylineHierarchy h = decompose(c, levels, Backend::Reference);
  std::vector<MatrixX3> local;
  for (int j = 0; j < levels; ++j)
    local.push_back(details_to_frames(h.details[j], segment_frames(reconstruct(h, j, Backend::Reference).points, c.closed)));
  return local;
}

MatrixX3 rebuild(const MatrixX3& coarse, const std::vector<MatrixX3>& local, bool closed) {
  MatrixX3 c = coarse;
  for (const auto& d : local) c = synthesis_step(c, details_from_frames(d, segment_frames(c, closed)), closed, Backend::Reference);
  return c;
}

double size_of(const MatrixX3& X) { return (X.colwise().maxCoeff() - X.colwise().minCoeff()).norm(); }

}  // namespace

TEST_CASE("local frames: decomposition and reconstruction round-trip, 2-D and 3-D", "[curve][local_frames]") {
  for (const auto& [name, levels] : {std::pair<std::string, int>{"wave129.obj", 7}, {"helix257.obj", 8}, {"ring128.obj", 5}}) {
    const Polyline c = bundled(name);
    const std::vector<MatrixX3> local = frame_details(c, levels);
    const MatrixX3 back = rebuild(decompose(c, levels, Backend::Reference).coarse, local, c.closed);
    INFO(name);
    CHECK((back - c.points).cwiseAbs().maxCoeff() <= 1e-13 * size_of(c.points));
  }
}

TEST_CASE("local frames: details are invariant under rigid motions", "[curve][local_frames]") {
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()) * Eigen::AngleAxisd(-1.1, Vec3::UnitZ())).toRotationMatrix();
  const Eigen::RowVector3d shift(3.0, -2.0, 0.5);
  for (const auto& [name, levels] : {std::pair<std::string, int>{"wave129.obj", 7}, {"helix257.obj", 8}}) {
    const Polyline c = bundled(name);
    Polyline moved = c;
    moved.points = (c.points * R.transpose()).rowwise() + shift;
    const std::vector<MatrixX3> a = frame_details(c, levels), b = frame_details(moved, levels);
    INFO(name);
    // A straight polygon has no bend and so no intrinsic normal (detail_frames.h takes a world
    // axis): only levels whose polygon bends are rigid-invariant.
    const PolylineHierarchy h = decompose(c, levels, Backend::Reference);
    int bent = 0;
    for (int j = 0; j < levels; ++j) {
      const MatrixX3 poly = reconstruct(h, j, Backend::Reference).points;
      const Vec3 t0 = (poly.row(1) - poly.row(0)).normalized().transpose();
      bool bends = false;
      for (Eigen::Index i = 1; i + 1 < poly.rows(); ++i)
        bends |= ((poly.row(i + 1) - poly.row(i)).normalized().transpose() - t0).norm() > 1e-6;
      if (!bends) continue;
      ++bent;
      INFO("level " << j);
      CHECK((a[j] - b[j]).cwiseAbs().maxCoeff() <= 1e-12 * size_of(c.points));
    }
    CHECK(bent >= levels - 3);
    // And the global details are not (the point of the option).
    const PolylineHierarchy ha = decompose(c, levels, Backend::Reference), hb = decompose(moved, levels, Backend::Reference);
    CHECK((ha.details[1] - hb.details[1]).cwiseAbs().maxCoeff() > 1e-2 * size_of(c.points));
  }
}

TEST_CASE("local frames: the attracting curve stays nearer the lengths on a rotated edit at low w", "[curve][local_frames]") {
  const Polyline wave = bundled("wave129.obj");
  const Recipe recipe(0.01);
  const auto solver = trust_region();
  const Eigen::VectorXd l = segment_lengths(wave.points, false);
  // The last coarse control point swung up: the chord turns by ~30 degrees and shortens a little.
  const Vec3 chord = (wave.points.row(128) - wave.points.row(0)).transpose();
  const Vec3 up = Vec3::UnitZ().cross(chord);
  const CurveMove swing = by(-1, -0.15 * chord + 0.5 * up);
  for (int w : {0, 1, 2}) {
    EditingOptions global, local;
    global.details = DetailFrames::Global;
    local.details = DetailFrames::LocalFrames;
    const EditStages g = run_editing_loop(wave, 7, make_edit(0, w, {swing}, global), recipe.objective, *solver, Backend::Optimized);
    const EditStages f = run_editing_loop(wave, 7, make_edit(0, w, {swing}, local), recipe.objective, *solver, Backend::Optimized);
    const double eg = measure_curve(g.attracting, false, l, g.attracting).length_error_max;
    const double ef = measure_curve(f.attracting, false, l, f.attracting).length_error_max;
    INFO("w = " << w << ": C_A length error global " << eg << ", local frames " << ef);
    CHECK(ef < eg);
    REQUIRE(f.solve.converged());
    CHECK(measure_curve(f.final, false, l, f.attracting).length_error_max <= 1e-11);
  }
  // No move: local frames reproduce the reference bit for bit.
  EditingOptions local;
  local.details = DetailFrames::LocalFrames;
  const EditStages none = run_editing_loop(wave, 7, make_edit(2, 4, {}, local), recipe.objective, *solver, Backend::Optimized);
  CHECK((none.edited - wave.points).cwiseAbs().maxCoeff() <= 1e-15);
}
