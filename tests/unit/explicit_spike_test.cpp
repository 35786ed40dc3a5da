// The explicit step of Sauvage et al. §4.1 never leaves a length wrong in silence: a spike whose
// midpoint overshoots its chord (a longer than the chord plus b) has no midpoint that keeps both
// children once the chord shrinks; such midpoints are counted and the lengths the step left
// measured, on both ways of handling stretched segments.
#include <catch2/catch.hpp>

#include "fairshape/core/config.h"
#include "fairshape/curve_design/editing_loop.h"
#include "fairshape/curve_design/explicit_length.h"
#include "fairshape/curves/multires_polyline.h"
#include "fairshape/io/mesh_io.h"

using namespace fairshape;

namespace {

// The bundled wave with point 65 thrown beyond point 66 along the level-6 chord 64-66: the
// child 64-65 is as long as the chord plus the child 65-66 (a folded spike).
Polyline spiky_wave(double overshoot) {
  Polyline c = read_polyline(std::string(FAIRSHAPE_SOURCE_DIR) + "/data/curves/wave129.obj");
  const Eigen::RowVector3d P = c.points.row(64), Q = c.points.row(66);
  c.points.row(65) = Q + overshoot * (Q - P) + Eigen::RowVector3d(0, 1e-3, 0);
  return c;
}

CurveEdit compress(double scale, ExplicitStep way) {
  CurveEdit edit;
  edit.edit_level = 0;
  edit.wrinkle_level = 6;
  edit.options.explicit_step = way;
  CurveMove mv;
  mv.index = -1;
  mv.chord_scale = scale;
  edit.moves.push_back(mv);
  return edit;
}

}  // namespace

TEST_CASE("explicit step on a spike: unplaceable midpoints counted, the lengths it left measured", "[sauvage][explicit]") {
  Config none;
  const auto bending = curve_components().energies.create("bending", Backend::Reference, none);
  const auto lengths = curve_components().constraints.create("segment_lengths", Backend::Reference, none);
  CurveObjective objective;
  objective.smoothness = bending.get();
  objective.beta = 0.5;
  objective.constraints = {lengths.get()};
  for (ExplicitStep way : {ExplicitStep::Local, ExplicitStep::Sweep}) {
    CAPTURE(way == ExplicitStep::Local ? "local" : "sweep");
    // Without the spike every midpoint is placed and every level-7 length kept.
    const Polyline wave = read_polyline(std::string(FAIRSHAPE_SOURCE_DIR) + "/data/curves/wave129.obj");
    const EditStages smooth = prepare_editing_loop(wave, 7, compress(0.95, way), objective, Backend::Optimized).stages;
    CHECK(smooth.explicit_step.unplaceable_midpoints == 0);
    CHECK(smooth.explicit_step.length_error < 1e-12);
    // With it, a 5 % compression shortens the spike's chord below a − b.
    const Polyline spiky = spiky_wave(3.0);
    const EditStages s = prepare_editing_loop(spiky, 7, compress(0.95, way), objective, Backend::Optimized).stages;
    CHECK(s.explicit_step.unplaceable_midpoints >= 1);
    CHECK(s.explicit_step.length_error > 1e-3);
    // The measure is the attracting curve's own: its level-7 (finest) lengths against the reference's.
    const Eigen::VectorXd ref = segment_lengths(spiky.points, false), got = segment_lengths(s.attracting, false);
    CHECK((got - ref).cwiseAbs().cwiseQuotient(ref).maxCoeff() == Approx(s.explicit_step.length_error).epsilon(1e-9));
  }
}

TEST_CASE("explicit step: a placeable midpoint is never counted, whatever the chord", "[sauvage][explicit]") {
  MatrixX3 coarse(3, 3);
  coarse << 0, 0, 0, 1, 0, 0, 2, 0, 0;
  Eigen::VectorXd target(4);
  target << 0.7, 0.4, 0.5, 0.5;
  CHECK(count_unplaceable_midpoints(coarse, target, false) == 0);  // |a − b| = 0.3 < 1
  target[0] = 1.5;
  CHECK(count_unplaceable_midpoints(coarse, target, false) == 1);  // |a − b| = 1.1 > 1
}
