// Truly adaptive against uniform evaluation (Khodakovsky & Schröder, "Fine level feature editing
// for subdivision surfaces", §2.5): a small feature drawn on the finest level of
// a bundled closed model refined until the uniform hierarchy has more than a million vertices.
//   uniform:  the whole Loop hierarchy, the feature applied (FeaturedSurface, drawn-level
//             profile), then the adaptive output thinned from it (adaptive_mesh) — what a run
//             did before;
//   adaptive: the sparse hierarchy refined only where the feature needs it (evaluate_adaptive),
//             and with the flatness test on the whole surface as well (surface_angle_deg 2).
// Time: medians of the repetitions. Peak memory: each variant once in a forked child, the peak
// resident set it adds to what it started with (`peak_added_MiB`; `idle_added_MiB` is a child
// that does nothing, forked just before). Triangles: of the output mesh. Model and depth: FAIRSHAPE_ADAPTIVE_BENCH_MESH
// (default data/homer.off) and FAIRSHAPE_ADAPTIVE_BENCH_LEVELS (default 4: 1,261,570 vertices).
#include <benchmark/benchmark.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <string>

#include "fairshape/feature/adaptive_evaluation.h"
#include "fairshape/feature/adaptive_mesh.h"
#include "fairshape/feature/featured_surface.h"
#include "fairshape/feature/level_attachment.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/subdivision/multires_surface.h"

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
    // A curve between the centres of two faces two rings apart where the model is flattest
    // (the face whose two-ring normals turn least), attached on the finest level by following
    // the parameter points down (level_attachment.h).
    const SurfaceMesh& m = q.base;
    const auto normal = [&](int f) {
      const auto v = m.face_vertices(f);
      return Vec3((m.position(v[1]) - m.position(v[0])).cross(m.position(v[2]) - m.position(v[0])).normalized());
    };
    const auto two_ring = [&](int f) {
      std::vector<int> out;
      for (int v : m.face_vertices(f))
        for (int w : m.vertex_neighbors(v))
          for (int g : m.vertex_faces(w)) out.push_back(g);
      return out;
    };
    int start = 0, far = -1;
    double best = 1e9;
    for (int f = 0; f < m.n_faces(); ++f) {
      double turn = 0;
      for (int g : two_ring(f)) turn = std::max(turn, std::acos(std::clamp(normal(f).dot(normal(g)), -1.0, 1.0)));
      if (turn < best) best = turn, start = f;
    }
    double far_distance = 0;
    const auto centre = [&](int f) {
      const auto v = m.face_vertices(f);
      return Vec3((m.position(v[0]) + m.position(v[1]) + m.position(v[2])) / 3);
    };
    for (int g : two_ring(start))
      if (const double d = (centre(g) - centre(start)).norm(); d > far_distance) far_distance = d, far = g;
    std::vector<SurfacePoint> points{{start, Vec3::Constant(1.0 / 3)}, {far, Vec3::Constant(1.0 / 3)}};
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
  long long faces_computed = 0, finest_faces_computed = 0;
  int passes = 1;
};

Outcome uniform_evaluation() {
  const Problem& p = problem();
  FeaturedSurface fs(MultiresSurface(p.base, p.opt, p.levels, Backend::Optimized), Backend::Optimized,
                     ProfileTarget::DrawnLevel);
  fs.add(p.feature);
  const AdaptiveMesh a = adaptive_mesh(fs.result(), 0, p.feature.params.flatness_angle_deg);
  long long faces = 0;
  for (int k = 0; k <= p.levels; ++k) faces += fs.result().mesh(k).n_faces();
  return {a.mesh.n_faces(), a.mesh.n_vertices(), faces, fs.result().mesh(p.levels).n_faces()};
}

Outcome adaptive_evaluation(double surface_angle) {
  const Problem& p = problem();
  AdaptiveEvaluationOptions o;
  o.surface_angle_deg = surface_angle;
  const AdaptiveEvaluation a = evaluate_adaptive(p.base, p.opt, p.levels, {p.feature}, o);
  return {a.mesh.n_faces(), a.mesh.n_vertices(), a.faces_computed(), a.levels.back().n_local_faces(), a.passes};
}

// Resident set figures of this process from /proc/self/status (kB), −1 if absent.
long status_kib(const char* field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::string key = std::string(field) + ":";
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0) return std::atol(line.c_str() + key.size());
  return -1;
}

// The peak memory `work` adds (MiB), run once in a forked child: the child resets its peak
// resident set to the current one (writing 5 to /proc/self/clear_refs), runs the work and
// reports VmHWM − VmRSS at the start through a pipe. (ru_maxrss would count the parent's
// resident pages the child shares, and keeps them across exec.)
double child_peak_rss_mib(const std::function<void()>& work) {
  int fd[2];
  if (pipe(fd) != 0) return -1;
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    { std::ofstream("/proc/self/clear_refs") << "5"; }
    const long start = status_kib("VmRSS");
    work();
    const long peak = status_kib("VmHWM");
    const double mib = start >= 0 && peak >= 0 ? (peak - start) / 1024.0 : -1;
    (void)!write(fd[1], &mib, sizeof mib);
    _exit(0);
  }
  close(fd[1]);
  double mib = -1;
  (void)!read(fd[0], &mib, sizeof mib);
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  return mib;
}

void report(benchmark::State& state, const Outcome& o, double rss, double baseline) {
  const Problem& p = problem();
  state.counters["triangles"] = o.triangles;
  state.counters["vertices"] = o.vertices;
  state.counters["faces_computed"] = static_cast<double>(o.faces_computed);
  state.counters["finest_faces_computed"] = static_cast<double>(o.finest_faces_computed);
  state.counters["passes"] = o.passes;
  state.counters["peak_added_MiB"] = rss;
  state.counters["idle_added_MiB"] = baseline;
  state.counters["uniform_finest_faces"] = static_cast<double>(p.base.n_faces()) * (1 << (2 * p.levels));
}

// Peak memory of each variant, measured in main() before any benchmark has run: a child forked
// later would reuse the parent's freed (still resident) heap and show less than it needs.
struct Memory {
  double idle = -1, uniform = -1, adaptive0 = -1, adaptive2 = -1;
};
Memory& memory() {
  static Memory m;
  return m;
}

void BM_UniformEvaluation(benchmark::State& state) {
  Outcome o;
  for (auto _ : state) o = uniform_evaluation();
  report(state, o, memory().uniform, memory().idle);
}

void BM_AdaptiveEvaluation(benchmark::State& state) {
  const double angle = static_cast<double>(state.range(0));
  Outcome o;
  for (auto _ : state) o = adaptive_evaluation(angle);
  report(state, o, angle > 0 ? memory().adaptive2 : memory().adaptive0, memory().idle);
}

}  // namespace

BENCHMARK(BM_UniformEvaluation)->Iterations(1)->Repetitions(3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_AdaptiveEvaluation)->Arg(0)->Arg(2)->Iterations(1)->Repetitions(3)->Unit(benchmark::kMillisecond)->UseRealTime();
int main(int argc, char** argv) {
  problem();
  Memory& m = memory();
  m.idle = child_peak_rss_mib([] {});
  m.uniform = child_peak_rss_mib([] { uniform_evaluation(); });
  m.adaptive0 = child_peak_rss_mib([] { adaptive_evaluation(0); });
  m.adaptive2 = child_peak_rss_mib([] { adaptive_evaluation(2); });
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
