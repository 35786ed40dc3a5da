// One step of a designer's drag (Sauvage, Hahmann and Bonneau §4: "interactive" editing, tens of
// ms per step in 2004) at 129 to 131,073 points, with the second-order check's share of it
// measured in the same run (papers/sauvage/README.md, "Second-order checks cheaper than the
// solve"). The edit: the wave's level-3 control point 4 (its middle) moved by 1 % of the chord
// sideways, solved on the edit's support (the defaults of a run), by the default solver
// (linearized, Newton, length tolerance 1e-8, stationarity 1e-8). Each iteration is one drag
// step of a CurveSession (curve_session.h), as the interactive editor takes them: the handle
// goes back and forth, each step from the curve the previous one left. Counters per step:
// step_ms (the session's step: editing loop and the step's own checks), solve_ms (the loop: the
// solve with its second-order check), session_check_ms (the step's checks on its result),
// check_ms (the second-order check alone, re-timed on every window at the answer), check_share
// = check_ms / step_ms, window_points (the largest window), points.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>

#include "curve_wave.h"
#include "fairshape/core/config.h"
#include "fairshape/core/timer.h"
#include "fairshape/curve_design/curve_session.h"
#include "fairshape/curve_design/second_order.h"

using namespace fairshape;

namespace {

Polyline wave(int k) { return curve_wave(k); }

CurveEdit drag_step(int k) {
  CurveEdit e;  // default EditingOptions: local explicit step, local frames, support windows, plane kept
  e.edit_level = 3;
  e.wrinkle_level = k - 3;  // the explicit step three levels below the finest, as BM_EditScaling
  CurveMove mv;
  mv.index = 4;
  mv.offset = Vec3(0, 0.02, 0);
  e.moves = {mv};
  return e;
}

const char* const kModes[] = {"inertia", "dense", "off"};

// arg 0: log2 segments; arg 1: 0 inertia (the default), 1 dense (the check before), 2 off.
void BM_DragStep(benchmark::State& state) {
  const int k = static_cast<int>(state.range(0));
  const SecondOrderMode mode = static_cast<SecondOrderMode>(state.range(1));
  Config none;
  CurveEditSettings settings;
  settings.smoothness = curve_components().energies.create("bending", Backend::Optimized, none);
  settings.constraints.push_back(curve_components().constraints.create("segment_lengths", Backend::Optimized, none));
  // Length tolerance 1e-8: the rounding floor grows like n·ε (BM_EditScaling); Newton: the
  // paper's linearization needs more than the 200-solve budget from this start above 4k points.
  Config sc(YAML::Load(std::string("{length_tolerance: 1.0e-8, linearized: {linearization: newton}, second_order: ") +
                       kModes[state.range(1)] + "}"),
            "solver");
  settings.solver = curve_components().solvers.create("linearized", Backend::Optimized, sc);
  settings.beta = 0.5;  // the run's default
  const Polyline curve = wave(k);
  CurveSession session(curve, k, std::move(settings));
  CurveEdit edit = drag_step(k);
  double step_s = 0, solve_s = 0, session_check_s = 0, check_s = 0;
  int window_points = 0, solves = 0;
  for (auto _ : state) {
    const Timer step;
    const CurveStep r = session.edit(edit);
    step_s = step.seconds();
    solve_s = r.solve_s;
    session_check_s = r.check_s;
    if (!r.stages.solve.converged()) {
      state.SkipWithError(r.summary.message.c_str());
      break;
    }
    solves = r.stages.solve.solves;
    benchmark::DoNotOptimize(r.curve().data());
    // The second-order check alone, as the solver made it at the answer, window by window (not
    // timed above), and the next step's move: back where this one came from.
    state.PauseTiming();
    CurveEdit same = edit;
    same.options = session.settings().editing;
    const PreparedCurveEdit prepared = prepare_editing_loop(Polyline{r.stages.reference, curve.closed}, k, same,
                                                            session.settings().objective(), Backend::Optimized, &curve);
    const Timer check;
    for (const EditWindow& w : prepared.windows) {
      MatrixX3 X(static_cast<Eigen::Index>(w.points.size()), 3);
      for (std::size_t i = 0; i < w.points.size(); ++i) X.row(static_cast<Eigen::Index>(i)) = r.curve().row(w.points[i]);
      benchmark::DoNotOptimize(second_order_check(*w.problem, X, mode, false).min_eigenvalue);
      window_points = std::max(window_points, static_cast<int>(w.points.size()));
    }
    if (prepared.windows.empty()) {
      benchmark::DoNotOptimize(second_order_check(*prepared.problem, r.curve(), mode, false).min_eigenvalue);
      window_points = curve.n_points();
    }
    check_s = check.seconds();
    edit.moves[0].offset = -edit.moves[0].offset;
    state.ResumeTiming();
  }
  state.counters["points"] = curve.n_points();
  state.counters["window_points"] = window_points;
  state.counters["solves"] = solves;
  state.counters["step_ms"] = 1e3 * step_s;
  state.counters["solve_ms"] = 1e3 * solve_s;
  state.counters["session_check_ms"] = 1e3 * session_check_s;
  state.counters["check_ms"] = 1e3 * check_s;
  state.counters["check_share"] = step_s > 0 ? check_s / step_s : 0;
  state.counters["us_per_point"] = 1e6 * step_s / curve.n_points();
}
// 2^7+1 … 2^17+1 points with the default check (and 2^12+1 = 4,097, the goal's largest size);
// the dense check where it is allowed (its windows ≤ 600 points: the 129-point curve and the
// 1,025-point one, whose ~500-point windows it takes seconds on) for the before/after ratio.
BENCHMARK(BM_DragStep)->ArgNames({"log2_segments", "mode"})
    ->ArgsProduct({{7, 10, 12, 14, 17}, {0}})
    ->ArgsProduct({{7, 10}, {1}})
    ->ArgsProduct({{7, 10, 12, 14, 17}, {2}})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
