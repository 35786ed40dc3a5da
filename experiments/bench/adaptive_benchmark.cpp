// Truly adaptive against uniform evaluation (Khodakovsky & Schröder, "Fine level feature editing
// for subdivision surfaces", §2.5; issue 24 part 3): a small feature drawn on the finest level of
// a bundled closed model refined until the uniform hierarchy has more than a million vertices.
//   uniform:  the whole Loop hierarchy, the feature applied (FeaturedSurface, drawn-level
//             profile), then the adaptive output thinned from it (adaptive_mesh) — what a run
//             did before;
//   adaptive: the sparse hierarchy refined only where the feature needs it (evaluate_adaptive),
//             and with the flatness test on the whole surface as well (surface_angle_deg 2).
// Time: medians of the repetitions. Peak memory: each variant once in a forked child (the
// child's ru_maxrss, which starts from the parent's resident set: `rss_baseline_MiB` is a child
// that does nothing). Triangles: of the output mesh. Model and depth: FAIRSHAPE_ADAPTIVE_BENCH_MESH
// (default data/homer.off) and FAIRSHAPE_ADAPTIVE_BENCH_LEVELS (default 4: 1,261,570 vertices).
#include <benchmark/benchmark.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <functional>
#include <string>

#include "feature/adaptive_evaluation.h"
#include "feature/adaptive_mesh.h"
#include "feature/featured_surface.h"
#include "feature/level_attachment.h"
#include "io/mesh_io.h"
#include "subdivision/multires_surface.h"

using namespace fairshape;
using namespace fairshape::feature;

namespace {

struct Problem {
  SurfaceMesh base;
  SubdivisionOptions opt;
  int levels = 4;
  FeatureCurve feature;
};

const Problem& problem() {
  static const Problem p = [] {
    Problem q;
    const char* mesh = std::getenv("FAIRSHAPE_ADAPTIVE_BENCH_MESH");
    const char* levels = std::getenv("FAIRSHAPE_ADAPTIVE_BENCH_LEVELS");
    q.base = read_mesh(mesh ? std::string(mesh) : std::string(FAIRSHAPE_SOURCE_DIR) + "/data/homer.off");
    q.levels = levels ? std::atoi(levels) : 4;
    q.opt.scheme = SchemeType::Loop;
    // A curve from the centre of face 0 to the centre of a face two rings away, attached on the
    // finest level by following the parameter points down (level_attachment.h).
    const SurfaceMesh& m = q.base;
    int far = -1;
    for (int h : m.outgoing_halfedges(m.face_vertices(0)[0])) {
      const int v = m.to_vertex(h);
      for (int g : m.vertex_faces(v))
        if (g != 0 && far < 0 && m.face_vertices(g)[0] != m.face_vertices(0)[0] &&
            m.face_vertices(g)[1] != m.face_vertices(0)[0] && m.face_vertices(g)[2] != m.face_vertices(0)[0])
          far = g;
    }
    std::vector<SurfacePoint> points{{0, Vec3::Constant(1.0 / 3)}, {far, Vec3::Constant(1.0 / 3)}};
    for (int k = 0; k < q.levels; ++k)
      for (SurfacePoint& p : points) p = child_point(p);
    double edge = 0;
    for (int e = 0; e < m.n_edges(); ++e) edge += (m.position(m.from_vertex(2 * e)) - m.position(m.to_vertex(2 * e))).norm();
    edge /= m.n_edges() * double(1 << q.levels);  // mean finest edge, roughly
    q.feature.name = "ridge";
    q.feature.level = q.levels;
    q.feature.points = points;
    q.feature.params.radius = 6 * edge;
    q.feature.params.height = 2 * edge;
    q.feature.params.flatness_angle_deg = 2;
    return q;
  }();
  return p;
}

struct Outcome {
  int triangles = 0, vertices = 0;
  long long faces_computed = 0;
};

Outcome uniform_evaluation() {
  const Problem& p = problem();
  FeaturedSurface fs(MultiresSurface(p.base, p.opt, p.levels, Backend::Optimized), Backend::Optimized,
                     ProfileTarget::DrawnLevel);
  fs.add(p.feature);
  const AdaptiveMesh a = adaptive_mesh(fs.result(), 0, p.feature.params.flatness_angle_deg);
  long long faces = 0;
  for (int k = 0; k <= p.levels; ++k) faces += fs.result().mesh(k).n_faces();
  return {a.mesh.n_faces(), a.mesh.n_vertices(), faces};
}

Outcome adaptive_evaluation(double surface_angle) {
  const Problem& p = problem();
  AdaptiveEvaluationOptions o;
  o.surface_angle_deg = surface_angle;
  const AdaptiveEvaluation a = evaluate_adaptive(p.base, p.opt, p.levels, {p.feature}, o);
  return {a.mesh.n_faces(), a.mesh.n_vertices(), a.faces_computed()};
}

// Peak resident set (MiB) of `work` run once in a child process.
double child_peak_rss_mib(const std::function<void()>& work) {
  const pid_t pid = fork();
  if (pid == 0) {
    work();
    _exit(0);
  }
  int status = 0;
  rusage ru{};
  wait4(pid, &status, 0, &ru);
  return ru.ru_maxrss / 1024.0;  // KiB on Linux
}

void report(benchmark::State& state, const Outcome& o, double rss) {
  const Problem& p = problem();
  state.counters["triangles"] = o.triangles;
  state.counters["vertices"] = o.vertices;
  state.counters["faces_computed"] = static_cast<double>(o.faces_computed);
  state.counters["peak_rss_MiB"] = rss;
  state.counters["rss_baseline_MiB"] = child_peak_rss_mib([] {});
  state.counters["uniform_finest_faces"] = static_cast<double>(p.base.n_faces()) * (1 << (2 * p.levels));
}

void BM_UniformEvaluation(benchmark::State& state) {
  problem();
  const double rss = child_peak_rss_mib([] { uniform_evaluation(); });
  Outcome o;
  for (auto _ : state) o = uniform_evaluation();
  report(state, o, rss);
}

void BM_AdaptiveEvaluation(benchmark::State& state) {
  problem();
  const double angle = static_cast<double>(state.range(0));
  const double rss = child_peak_rss_mib([angle] { adaptive_evaluation(angle); });
  Outcome o;
  for (auto _ : state) o = adaptive_evaluation(angle);
  report(state, o, rss);
}

}  // namespace

BENCHMARK(BM_UniformEvaluation)->Iterations(1)->Repetitions(3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_AdaptiveEvaluation)->Arg(0)->Arg(2)->Iterations(1)->Repetitions(3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
