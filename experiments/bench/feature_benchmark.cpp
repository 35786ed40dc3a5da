// Khodakovsky & Schröder feature curves at scale: a 100-segment curve applied on a Loop level of
// 1,050,625 vertices (a curved 32 × 32 sheet refined 5 times), optimized (TBB) against the
// reference, and against the cost of one uniform Loop refinement of the same level (all in one
// process). The feature is fine-level: r = 8 edge lengths of that level. Goal: interactive,
// under 50 ms on 2 cores. Medians: --benchmark_repetitions.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "fairshape/feature/featured_surface.h"
#include "fairshape/feature/perturbation.h"
#include "fairshape/subdivision/multires_surface.h"
#include "fairshape/subdivision/subdivider.h"

using namespace fairshape;
using namespace fairshape::feature;

namespace {

SurfaceMesh curved_sheet(int n) {
  MatrixX3 V((n + 1) * (n + 1), 3);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = -1 + 2.0 * i / n, y = -1 + 2.0 * j / n;
      V.row(j * (n + 1) + i) << x, y, 0.12 * (x * x - 0.5 * y * y);
    }
  PolygonList faces;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      if ((i + j) % 2 == 0) faces.push_back({a, b, d}), faces.push_back({a, d, c});
      else faces.push_back({a, b, c}), faces.push_back({b, d, c});
    }
  return SurfaceMesh::from_polygons(V, faces);
}

SubdivisionOptions loop() {
  SubdivisionOptions o;
  o.scheme = SchemeType::Loop;
  return o;
}

struct Fixture {
  SurfaceMesh level;  // ~1M vertices at level 5
  MatrixX3 normals;
  FeatureCurve curve;
  explicit Fixture(int levels) {
    const MultiresSurface h(curved_sheet(32), loop(), levels, Backend::Optimized);
    level = h.mesh(levels);
    normals = loop_limit_normals(level);
    const TriangleSurface s(level, normals);
    // 101 points on a wave across the sheet: 100 segments.
    MatrixX3 P(101, 3);
    for (int k = 0; k <= 100; ++k) {
      const double x = -0.8 + 1.6 * k / 100.0, y = 0.3 * std::sin(3 * x);
      P.row(k) << x, y, 0.12 * (x * x - 0.5 * y * y);
    }
    curve.name = "wave";
    curve.points = project_to_surface(s, P, 0.01, "benchmark curve");
    curve.params.radius = 8 * 2.0 / (32 << levels);  // 8 edge lengths of the level
    curve.params.height = 0.004;
  }
};

// Level 5 (1,050,625 vertices) unless FAIRSHAPE_FEATURE_BENCH_LEVELS says otherwise (a smaller
// level makes instruction counts under callgrind affordable).
Fixture& fixture() {
  static Fixture f([] {
    const char* env = std::getenv("FAIRSHAPE_FEATURE_BENCH_LEVELS");
    return env ? std::atoi(env) : 5;
  }());
  return f;
}

// What one interactive edit of the curve costs: split the polygon, perturb the level.
void apply(benchmark::State& state, Backend backend) {
  Fixture& f = fixture();
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  const TriangleSurface s(f.level, f.normals);
  std::size_t moved = 0, segments = 0;
  for (auto _ : state) {
    const BaseCurve base = build_base_curve(s, f.curve);
    const LevelPerturbation d = compute_perturbation(s, {base}, backend);
    moved = d.vertices.size();
    segments = base.segments.size();
    benchmark::DoNotOptimize(d.displacement.data());
  }
  state.counters["vertices"] = static_cast<double>(f.level.n_vertices());
  state.counters["moved"] = static_cast<double>(moved);
  state.counters["segments_after_split"] = static_cast<double>(segments);
}

void BM_ApplyFeature_Optimized(benchmark::State& state) { apply(state, Backend::Optimized); }
void BM_ApplyFeature_Reference(benchmark::State& state) { apply(state, Backend::Reference); }

// The frames' normals for the whole level (done once per level edit, not per curve edit).
void BM_LevelNormals(benchmark::State& state) {
  Fixture& f = fixture();
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(loop_limit_normals(f.level).data());
}

// The peer: one uniform Loop step of the same level (topology, S and positions).
void BM_UniformLoopRefinement(benchmark::State& state) {
  Fixture& f = fixture();
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    const SurfaceMesh fine = subdivide_once(f.level, loop(), Backend::Optimized);
    benchmark::DoNotOptimize(fine.positions().data());
  }
}

// The visible-profile step against the paper's drawn-level semantics, same run:
// a whole hierarchy evaluated (every level's perturbation, the finer levels re-synthesized) with
// a feature drawn on level 2 of a curved 32 × 32 sheet refined 4 times (263,169 finest vertices),
// its profile made exact on the drawn level (the paper), the finest level, or the limit.
// Arg: 0 drawn_level, 1 finest, 2 limit.
void BM_EvaluateHierarchy(benchmark::State& state) {
  static const MultiresSurface h(curved_sheet(32), loop(), 4, Backend::Optimized);
  const ProfileTarget targets[] = {ProfileTarget::DrawnLevel, ProfileTarget::Finest, ProfileTarget::Limit};
  FeaturedSurface surface(h, Backend::Optimized, targets[state.range(0)]);
  const SurfaceMesh& level = h.mesh(2);
  const TriangleSurface s(level, loop_limit_normals(level));
  MatrixX3 P(21, 3);
  for (int k = 0; k <= 20; ++k) {
    const double x = -0.8 + 1.6 * k / 20.0, y = 0.3 * std::sin(3 * x);
    P.row(k) << x, y, 0.12 * (x * x - 0.5 * y * y);
  }
  FeatureCurve curve;
  curve.name = "wave";
  curve.level = 2;
  curve.points = project_to_surface(s, P, 0.01, "benchmark curve");
  curve.params.radius = 4 * 2.0 / (32 << 2);  // 4 edge lengths of level 2
  curve.params.height = 0.004;
  surface.add(curve);
  for (auto _ : state) {
    (void)surface.original();  // marks the surface for a new evaluation
    benchmark::DoNotOptimize(surface.result().mesh(4).positions().data());
  }
  state.counters["finest_vertices"] = static_cast<double>(h.mesh(4).n_vertices());
}

// A design step: the sheet of BM_EvaluateHierarchy (263,169 finest vertices,
// 351,153 over its 5 levels) with the wave on level 2 and two short ridges away from it, one on
// the finest level and one on level 2; each iteration moves one of the ridges by a tenth of its
// radius (back and forth) and evaluates the step, the whole hierarchy or its region.
// Args: {0 the finest-level ridge moves, 1 the level-2 one} × {0 whole, 1 region} ×
// {0 drawn_level, 2 limit}.
FeatureCurve sheet_curve(const MultiresSurface& h, int level, const std::vector<Vec3>& xy, double radius, double height,
                         const std::string& name) {
  const SurfaceMesh& m = h.mesh(level);
  const TriangleSurface s(m, loop_limit_normals(m));
  MatrixX3 P(static_cast<Eigen::Index>(xy.size()), 3);
  for (std::size_t k = 0; k < xy.size(); ++k) {
    const double x = xy[k].x(), y = xy[k].y();
    P.row(static_cast<Eigen::Index>(k)) << x, y, 0.12 * (x * x - 0.5 * y * y);
  }
  FeatureCurve c;
  c.name = name;
  c.level = level;
  c.points = project_to_surface(s, P, 0.01, "benchmark curve");
  c.params.radius = radius;
  c.params.height = height;
  return c;
}

void BM_DesignStep(benchmark::State& state) {
  static const MultiresSurface h(curved_sheet(32), loop(), 4, Backend::Optimized);
  const ProfileTarget targets[] = {ProfileTarget::DrawnLevel, ProfileTarget::Finest, ProfileTarget::Limit};
  const bool coarse = state.range(0) == 1;
  FeaturedSurface surface(h, Backend::Optimized, targets[state.range(2)]);
  surface.set_region_evaluation(state.range(1) == 1);
  std::vector<Vec3> wave;
  for (int k = 0; k <= 20; ++k) {
    const double x = -0.8 + 1.6 * k / 20.0;
    wave.emplace_back(x, 0.3 * std::sin(3 * x), 0);
  }
  surface.add(sheet_curve(h, 2, wave, 4 * 2.0 / (32 << 2), 0.004, "wave"));
  const double fine_r = 6 * 2.0 / (32 << 4), coarse_r = 3 * 2.0 / (32 << 2);
  const auto fine_at = [&](double dy) {
    return sheet_curve(h, 4, {Vec3(0.4, -0.7 + dy, 0), Vec3(0.6, -0.72 + dy, 0)}, fine_r, 0.5 * fine_r, "fine");
  };
  const auto coarse_at = [&](double dy) {
    return sheet_curve(h, 2, {Vec3(-0.6, -0.7 + dy, 0), Vec3(-0.3, -0.72 + dy, 0)}, coarse_r, 0.3 * coarse_r, "coarse");
  };
  const FeatureCurve moves[2] = {coarse ? coarse_at(0) : fine_at(0), coarse ? coarse_at(0.1 * coarse_r) : fine_at(0.1 * fine_r)};
  const int fine_id = surface.add(fine_at(0)), coarse_id = surface.add(coarse_at(0));
  const int moved = coarse ? coarse_id : fine_id;
  benchmark::DoNotOptimize(surface.result().mesh(4).positions().data());
  long long recomputed = 0, steps = 0;
  for (auto _ : state) {
    surface.replace(moved, moves[(++steps) % 2]);
    benchmark::DoNotOptimize(surface.result().mesh(4).positions().data());
    recomputed += surface.last_evaluation().vertices_recomputed;
  }
  long long total = 0;
  for (int k = 0; k <= h.levels(); ++k) total += h.mesh(k).n_vertices();
  state.counters["finest_vertices"] = static_cast<double>(h.mesh(4).n_vertices());
  state.counters["hierarchy_vertices"] = static_cast<double>(total);
  state.counters["recomputed"] = static_cast<double>(recomputed) / static_cast<double>(std::max(1LL, steps));
}

}  // namespace

BENCHMARK(BM_DesignStep)->ArgsProduct({{0, 1}, {0, 1}, {0, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_EvaluateHierarchy)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ApplyFeature_Optimized)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ApplyFeature_Reference)->Arg(1)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_LevelNormals)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_UniformLoopRefinement)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
