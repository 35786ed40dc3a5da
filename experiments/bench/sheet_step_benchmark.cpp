// One drag step of a Welch & Witkin session on a 32 × 32-span bicubic sheet (size 2, four corner
// pins, a lifted diagonal curve constraint, one point dragged): bspline::solve_sheet as a run
// calls it per step — assemble, (re)factor or reuse, solve, the constraint errors and the exact
// conflict checks — with and without the curve resolution probe (bspline/curve_fidelity.h), and
// the parts alone, so the checks' share of a step is read off one run; KKT and QR-penalty with
// their factorizations kept across the drag and factored every step (reuse_factorization: false),
// the same-run baseline. Medians: --benchmark_repetitions; the README's table
// (papers/welch-witkin/README.md, "A drag step and its checks") reads
//   --benchmark_filter='checks_only|Assemble|StepChecks' --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true --benchmark_out=papers/welch-witkin/data/bench/sheet_step_benchmark.json
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

#include "fairshape/bspline/curve_fidelity.h"
#include "fairshape/bspline/sheet_geometry.h"
#include "fairshape/bspline/sheet_session.h"
#include "fairshape/bspline/variational_sheet.h"
#include "fairshape/core/config.h"
#include "fairshape/core/summary.h"
#include "fairshape/qp/qp_solver.h"

using namespace fairshape;
using namespace fairshape::bspline;

namespace {

constexpr int kSpans = 32;
constexpr double kSize = 2, kH = kSize / kSpans;  // design units per span

struct DragSession {
  SheetShape shape;
  std::unique_ptr<VariationalSheet> sheet;
  SheetEnergy energy;
  std::vector<SheetConstraint> constraints;
  // steep: the handle 0.01 beside the curve asking 0.1 more than the curve there, so the curve's
  // pointwise error is above the probe's floor and the probe runs its solves (a legal design).
  explicit DragSession(bool steep = false) {
    shape.spans_u = shape.spans_v = kSpans;
    shape.span_size = {kH, kH};
    const HierarchicalSurface s(shape);
    SheetPlacement p;
    p.size_u = p.size_v = kSize;
    sheet = std::make_unique<VariationalSheet>(shape, initial_coefficients(p, s));
    energy.weights.alpha = 0.01 * Eigen::Matrix2d::Identity();
    for (const auto& [u, v] : {std::pair{0.125, 0.125}, {1.875, 0.125}, {0.125, 1.875}, {1.875, 1.875}}) {
      SheetConstraint pin;
      pin.u = u / kH, pin.v = v / kH;
      pin.target = Vec3(u, v, 0);
      constraints.push_back(pin);
    }
    SheetConstraint curve;  // the diagonal, lifted 0.3 in its middle by a cosine bump
    curve.kind = SheetConstraint::Kind::Curve;
    curve.curve.uv = {Eigen::Vector2d(0.25, 0.25) / kH, Eigen::Vector2d(1.75, 1.75) / kH};
    for (int k = 0; k <= 64; ++k) {
      const double t = k / 64.0, x = 0.25 + 1.5 * t, d = std::abs(t - 0.5) / 0.6;
      curve.curve.space.emplace_back(x, x, d < 1 ? 0.15 * (1 + std::cos(M_PI * d)) : 0.0);
    }
    constraints.push_back(curve);
    SheetConstraint handle;  // the dragged point, beside the curve
    const double d = 0.01 / std::sqrt(2.0), x = 0.25 + 1.5 * 0.2;  // the curve's t = 0.2 (height 0.0375)
    const Vec3 at = steep ? Vec3(x + d, x - d, 0.0375 + 0.1) : Vec3(1.5, 0.5, 0.2);
    handle.u = at.x() / kH, handle.v = at.y() / kH;
    handle.target = at;
    base_height = at.z();
    constraints.push_back(handle);
  }
  // The handle moved to the next position of a back-and-forth drag.
  double base_height = 0;
  void drag(int step) { constraints.back().target.z() = base_height + 0.01 * ((step % 2) ? 1 : -1); }
};

// options: the solver's block, e.g. "{reuse_factorization: false}" (every step factored, as
// before KKT and QR-penalty kept their factorizations across a drag).
std::unique_ptr<qp::QpSolver> make(const std::string& name, const std::string& options = "{}") {
  Config cfg(YAML::Load(options), "solver");
  return qp::qp_solver_registry().create(name, Backend::Optimized, cfg);
}

// A whole step as the sheet run takes it (solve_sheet), with the probe or the exact checks only.
void BM_SheetDragStep(benchmark::State& state, const std::string& solver_name, bool probe, bool steep,
                      const std::string& solver_options = "{}") {
  DragSession d(steep);
  auto solver = make(solver_name, solver_options);
  RefinementOptions options;
  options.curve_probe = probe;
  int step = 0;
  (void)solve_sheet(*d.sheet, d.energy, d.constraints, *solver, options, Backend::Optimized);  // the first factorization
  DesignReport r;
  for (auto _ : state) {
    d.drag(++step);
    r = solve_sheet(*d.sheet, d.energy, d.constraints, *solver, options, Backend::Optimized);
  }
  state.counters["dofs"] = d.sheet->surface().dof_count();
  state.counters["solve_ms"] = 1e3 * r.solve_s;
  state.counters["analyze_ms"] = 1e3 * r.analyze_s;
  state.counters["converged"] = r.qp.summary.termination == Termination::Converged;
  state.counters["energy"] = r.energy;
}

// The parts of a step alone: the program's assembly, and the checks every step keeps (pointwise
// constraint errors, the exact position and slope conflict checks).
void BM_SheetAssemble(benchmark::State& state) {
  DragSession d;
  for (auto _ : state) benchmark::DoNotOptimize(assemble(*d.sheet, d.energy, d.constraints, Backend::Optimized).H.nonZeros());
}

void BM_SheetStepChecks(benchmark::State& state) {
  DragSession d;
  auto solver = make("range_space");
  (void)solve_sheet(*d.sheet, d.energy, d.constraints, *solver, {}, Backend::Optimized);
  for (auto _ : state) {
    benchmark::DoNotOptimize(max_error(constraint_errors(*d.sheet, d.constraints)));
    benchmark::DoNotOptimize(curve_conflict(*d.sheet, d.constraints, 1e-3).has_value());
    benchmark::DoNotOptimize(curve_slope_conflict(*d.sheet, d.constraints, 1e-3).has_value());
  }
}

// The same drag through the session (bspline/sheet_session.h), as an editor's drag frame takes it:
// SheetSession::move with the probe off (it runs on release), the session's own checks included
// (each constraint measured on the sheet). The README's drag-frame goal (≤ 10 ms at 32 × 32) reads
//   --benchmark_filter=SessionDrag --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
void BM_SessionDrag(benchmark::State& state, const std::string& solver_name) {
  DragSession d;
  SheetSession session({"sheet"}, {*d.sheet}, SheetSessionOptions{d.energy, {}, Backend::Optimized}, make(solver_name));
  SheetEdits all;  // everything in one step: the first factorization
  for (const SheetConstraint& c : d.constraints) all.put.push_back({-1, {0, c}});
  const SheetStep installed = session.apply(all);
  const SheetHandle handle = installed.added.back();
  int step = 0;
  SheetStep r;
  for (auto _ : state) {
    d.drag(++step);
    r = session.move(handle, d.constraints.back().target, SheetChecks{false});
  }
  state.counters["dofs"] = session.sheet(0).surface().dof_count();
  state.counters["solve_ms"] = 1e3 * r.solve_s;
  state.counters["check_ms"] = 1e3 * r.check_s;
  state.counters["converged"] = r.summary.termination == Termination::Converged;
  state.counters["energy"] = r.energy;
}

}  // namespace

BENCHMARK_CAPTURE(BM_SessionDrag, kkt, std::string("kkt"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SessionDrag, range_space, std::string("range_space"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SheetDragStep, range_space_checks_only, std::string("range_space"), false, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SheetDragStep, range_space_with_probe, std::string("range_space"), true, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SheetDragStep, range_space_steep_checks_only, std::string("range_space"), false, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SheetDragStep, range_space_steep_with_probe, std::string("range_space"), true, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SheetDragStep, kkt_checks_only, std::string("kkt"), false, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SheetDragStep, kkt_with_probe, std::string("kkt"), true, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SheetDragStep, kkt_refactored_checks_only, std::string("kkt"), false, false,
                  std::string("{reuse_factorization: false}"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SheetDragStep, qr_penalty_checks_only, std::string("qr_penalty"), false, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SheetDragStep, qr_penalty_refactored_checks_only, std::string("qr_penalty"), false, false,
                  std::string("{reuse_factorization: false}"))->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SheetAssemble)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SheetStepChecks)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
