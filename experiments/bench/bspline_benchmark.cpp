// Welch & Witkin on a 32×32-span bicubic sheet with 100 point constraints and one curve
// constraint: the drag update with the prefactored KKT system (goal ≤ 10 ms), the factor and
// solve of every constrained solver with its accuracy against KKT (time to accuracy), the
// range-space solver adding one constraint (bordered Schur complement) against refactoring, a
// design step adding or removing eight pins (factor updated against refactored) at 16, 32 and
// 64 spans, and the energy
// assembly, reference against optimized. Medians: --benchmark_repetitions.
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>

#include "fairshape/bspline/hierarchical_surface.h"
#include "fairshape/bspline/surface_constraints.h"
#include "fairshape/bspline/thin_plate_energy.h"
#include "fairshape/core/config.h"
#include "fairshape/qp/qp_solver.h"
#include "fairshape/qp/range_space_solver.h"

using namespace fairshape;
using namespace fairshape::bspline;

namespace {

struct Sheet32 {
  HierarchicalSurface s{{32, 32, 3, false}};
  qp::QuadraticProgram qp;
  Eigen::MatrixXd b_dragged;
  ConstraintRows extra;
  Sheet32() {
    TensionWeights w;
    w.alpha = 0.01 * Eigen::Matrix2d::Identity();
    qp.H = thin_plate_hessian(s, w, Backend::Optimized);
    qp.K = thin_plate_square_root(s, w);
    qp.f = Eigen::MatrixXd::Zero(s.dof_count(), 3);
    std::vector<ConstraintRows> parts;
    // Points and curve sample one smooth height field, so the constraints are consistent.
    const auto height = [](double u, double v) { return 0.3 * std::sin(0.2 * u) * std::cos(0.15 * v); };
    for (int a = 0; a < 10; ++a)
      for (int b = 0; b < 10; ++b) {
        const double u = 1.6 + 3.2 * a, v = 1.6 + 3.2 * b;
        parts.push_back(point_rows(s, u, v, Vec3(u, v, height(u, v))));
      }
    CurveAttachment c;
    for (int k = 0; k <= 40; ++k) {
      const double t = k / 40.0;
      c.uv.emplace_back(3 + 26 * t, 16 + 6 * std::sin(3 * t));
      c.space.emplace_back(c.uv.back().x(), c.uv.back().y(), height(c.uv.back().x(), c.uv.back().y()));
    }
    parts.push_back(curve_rows(s, c, CurveQuadrature::Exact));
    const ConstraintRows all = stack(parts, s.dof_count());
    qp.A = all.A;
    qp.b = all.C;
    b_dragged = qp.b;
    b_dragged(45, 2) += 0.5;  // one pin dragged up
    extra = point_rows(s, 20.3, 9.1, Vec3(20.3, 9.1, -0.4));
  }
};

const Sheet32& sheet() {
  static const Sheet32 s;
  return s;
}

std::unique_ptr<qp::QpSolver> make(const std::string& name, const std::string& yaml = "{}") {
  Config cfg(YAML::Load(yaml), "solver");
  return qp::qp_solver_registry().create(name, Backend::Optimized, cfg);
}

const Eigen::MatrixXd& kkt_solution() {
  static const Eigen::MatrixXd p = [] {
    auto s = make("kkt");
    s->analyze(sheet().qp);
    return s->solve(sheet().qp.f, sheet().qp.b).p;
  }();
  return p;
}

void BM_DragUpdate(benchmark::State& state, const std::string& solver) {
  const Sheet32& sh = sheet();
  auto s = make(solver);
  s->analyze(sh.qp);
  for (auto _ : state) benchmark::DoNotOptimize(s->solve(sh.qp.f, sh.b_dragged).p.data());
  state.counters["dofs"] = sh.s.dof_count();
  state.counters["constraint_rows"] = static_cast<double>(sh.qp.A.rows());
}

// Factor + solve, with the solution's relative error against KKT and its constraint residual.
void BM_FactorSolve(benchmark::State& state, const std::string& solver, const std::string& yaml) {
  const Sheet32& sh = sheet();
  qp::QpReport r;
  for (auto _ : state) {
    auto s = make(solver, yaml);
    s->analyze(sh.qp);
    r = s->solve(sh.qp.f, sh.qp.b);
  }
  state.counters["error_vs_kkt"] = (r.p - kkt_solution()).norm() / kkt_solution().norm();
  state.counters["constraint_residual"] = r.constraint_residual;
}

void BM_AddConstraint(benchmark::State& state, bool update) {
  const Sheet32& sh = sheet();
  qp::QuadraticProgram grown = sh.qp;
  const ConstraintRows all = stack({{sh.qp.A, sh.qp.b}, sh.extra}, sh.s.dof_count());
  grown.A = all.A;
  grown.b = all.C;
  for (auto _ : state) {
    state.PauseTiming();
    qp::RangeSpaceSolver s;
    s.analyze(sh.qp);
    state.ResumeTiming();
    if (update) {
      s.add_rows(sh.extra.A);
      benchmark::DoNotOptimize(s.solve(grown.f, grown.b).p.data());
    } else {  // a fresh solver: analyze() on `s` would recognise the rows and border the new one
      qp::RangeSpaceSolver fresh;
      fresh.analyze(grown);
      benchmark::DoNotOptimize(fresh.solve(grown.f, grown.b).p.data());
    }
  }
}

// A design step that adds or removes point constraints, at several sheet sizes: the range-space
// solver's update of its factor (bordered rows, CHOLMOD downdate) against analyzing the new
// program from scratch. Arg: spans per side (the same 100 pins and curve pattern, scaled).
struct RowStep {
  HierarchicalSurface s;
  qp::QuadraticProgram before, after;  // after: before plus 8 pins (or before minus them)
  SparseMatrix extra;
  explicit RowStep(int spans) : s({spans, spans, 3, false}) {
    TensionWeights w;
    w.alpha = 0.01 * Eigen::Matrix2d::Identity();
    before.H = thin_plate_hessian(s, w, Backend::Optimized);
    before.K = thin_plate_square_root(s, w);
    before.f = Eigen::MatrixXd::Zero(s.dof_count(), 3);
    const double h = spans / 10.0;
    std::vector<ConstraintRows> pins, more;
    for (int a = 0; a < 10; ++a)
      for (int b = 0; b < 10; ++b) pins.push_back(point_rows(s, h * (a + 0.5), h * (b + 0.5), Vec3(a, b, 0.1 * std::sin(a + b))));
    for (int k = 0; k < 8; ++k) more.push_back(point_rows(s, h * (k + 1), h * 4.9, Vec3(k, 4, -0.2)));
    const ConstraintRows base = stack(pins, s.dof_count());
    const ConstraintRows added = stack(more, s.dof_count());
    before.A = base.A;
    before.b = base.C;
    after = before;
    const ConstraintRows all = stack({base, added}, s.dof_count());
    after.A = all.A;
    after.b = all.C;
    extra = added.A;
  }
};

const RowStep& row_step(int spans) {
  static std::map<int, std::unique_ptr<RowStep>> cache;
  auto& p = cache[spans];
  if (!p) p = std::make_unique<RowStep>(spans);
  return *p;
}

enum class RowChange { AddUpdate, AddRefactor, RemoveUpdate, RemoveRefactor };

void BM_RowStep(benchmark::State& state, RowChange change) {
  const RowStep& p = row_step(static_cast<int>(state.range(0)));
  const bool adding = change == RowChange::AddUpdate || change == RowChange::AddRefactor;
  const qp::QuadraticProgram& from = adding ? p.before : p.after;
  const qp::QuadraticProgram& to = adding ? p.after : p.before;
  std::vector<int> last_rows;
  for (int k = 0; k < 8; ++k) last_rows.push_back(static_cast<int>(p.before.A.rows()) + k);
  for (auto _ : state) {
    state.PauseTiming();
    qp::RangeSpaceSolver s;
    s.analyze(from);
    state.ResumeTiming();
    if (change == RowChange::AddUpdate) s.add_rows(p.extra);
    if (change == RowChange::RemoveUpdate) s.remove_rows(last_rows);
    if (change == RowChange::AddUpdate || change == RowChange::RemoveUpdate) {
      benchmark::DoNotOptimize(s.solve(to.f, to.b).p.data());
      continue;
    }
    // A fresh solver: analyze() on the old one would recognise the rows and update its factor.
    qp::RangeSpaceSolver fresh;
    fresh.analyze(to);
    benchmark::DoNotOptimize(fresh.solve(to.f, to.b).p.data());
  }
  state.counters["dofs"] = p.s.dof_count();
  state.counters["rows"] = static_cast<double>(to.A.rows());
}

void BM_Hessian(benchmark::State& state, Backend backend) {
  const Sheet32& sh = sheet();
  TensionWeights w;
  for (auto _ : state) benchmark::DoNotOptimize(thin_plate_hessian(sh.s, w, backend).nonZeros());
}

}  // namespace

BENCHMARK_CAPTURE(BM_DragUpdate, kkt, std::string("kkt"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DragUpdate, qr_penalty, std::string("qr_penalty"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DragUpdate, range_space, std::string("range_space"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FactorSolve, kkt, std::string("kkt"), std::string("{}"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FactorSolve, range_space, std::string("range_space"), std::string("{}"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FactorSolve, qr_penalty_mu1e2_steps0, std::string("qr_penalty"), std::string("{mu: 100, refinement_steps: 0}"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FactorSolve, qr_penalty_mu1e2_steps2, std::string("qr_penalty"), std::string("{mu: 100, refinement_steps: 2}"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FactorSolve, qr_penalty_mu1e2_steps5, std::string("qr_penalty"), std::string("{mu: 100, refinement_steps: 5}"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FactorSolve, qr_penalty_mu1e4_steps0, std::string("qr_penalty"), std::string("{mu: 10000, refinement_steps: 0}"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FactorSolve, qr_penalty_mu1e4_steps2, std::string("qr_penalty"), std::string("{mu: 10000, refinement_steps: 2}"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AddConstraint, bordered_schur, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AddConstraint, refactor, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RowStep, add_update, RowChange::AddUpdate)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RowStep, add_refactor, RowChange::AddRefactor)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RowStep, remove_update, RowChange::RemoveUpdate)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RowStep, remove_refactor, RowChange::RemoveRefactor)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Hessian, reference, Backend::Reference)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Hessian, optimized, Backend::Optimized)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
