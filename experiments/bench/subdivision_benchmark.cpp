// Uniform Catmull-Clark refinement of the bundled cow, levels 1-4 (level 4 = 1,114,370
// vertices), fairshape against OpenSubdiv Far measured in the same process:
//   topology:  OpenSubdiv TopologyRefiner (create + RefineUniform) vs fairshape's direct
//              child half-edge construction (refine_topology) at every level, 1 and 2 threads;
//   primvar:   OpenSubdiv PrimvarRefiner::Interpolate through the levels vs fairshape's
//              prebuilt operators S_l applied level by level (row-parallel), and vs its
//              matrix-free step (stencils generated on the fly, like OpenSubdiv), 1 and 2 threads;
//   stencils:  OpenSubdiv StencilTable::UpdateValues (level 0 -> L in one table) vs
//              fairshape's composed operator S_{L-1}...S_0 applied once;
//   interactive: one drag step of Boier-Martin et al.'s interactive mode (the Figure 2 edit
//              solved on level 0, factored once, its deformation subdivided to level L),
//              the work OpenSubdiv's primvar refinement of the same ladder is judged against.
// Arguments: /level/threads.
#include <benchmark/benchmark.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/stencilTable.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <tbb/global_control.h>

#include <map>

#include "cow_edit_problem.h"
#include "fairshape/design/multilevel_edit.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/subdivision/apply.h"
#include "fairshape/subdivision/subdivider.h"

namespace fairshape {
namespace {

namespace Osd = OpenSubdiv;
using Factory = Osd::Far::TopologyRefinerFactory<Osd::Far::TopologyDescriptor>;

const SurfaceMesh& cow() {
  static const SurfaceMesh m = read_mesh(std::string(FAIRSHAPE_SOURCE_DIR) + "/data/cow.off");
  return m;
}

struct OsdInput {
  std::vector<int> sizes, indices;
  Osd::Far::TopologyDescriptor descriptor;
};
const OsdInput& osd_input() {
  static const OsdInput in = [] {
    OsdInput r;
    for (const auto& f : cow().polygons()) {
      r.sizes.push_back(static_cast<int>(f.size()));
      r.indices.insert(r.indices.end(), f.begin(), f.end());
    }
    r.descriptor.numVertices = cow().n_vertices();
    r.descriptor.numFaces = cow().n_faces();
    r.descriptor.numVertsPerFace = r.sizes.data();
    r.descriptor.vertIndicesPerFace = r.indices.data();
    return r;
  }();
  return in;
}

std::unique_ptr<Osd::Far::TopologyRefiner> osd_refine(int levels) {
  Osd::Sdc::Options o;
  o.SetVtxBoundaryInterpolation(Osd::Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
  std::unique_ptr<Osd::Far::TopologyRefiner> r(
      Factory::Create(osd_input().descriptor, Factory::Options(Osd::Sdc::SCHEME_CATMARK, o)));
  r->RefineUniform(Osd::Far::TopologyRefiner::UniformOptions(levels));
  return r;
}

struct OsdVertex {
  double p[3];
  void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0; }
  void AddWithWeight(const OsdVertex& s, double w) {
    p[0] += w * s.p[0];
    p[1] += w * s.p[1];
    p[2] += w * s.p[2];
  }
};

// fairshape's levels and operators, built once per level count.
struct Ladder {
  std::vector<SurfaceMesh> meshes;
  std::vector<RowSparseMatrix> S;
  RowSparseMatrix composed;
};
const Ladder& ladder(int levels) {
  static std::map<int, Ladder> cache;
  auto it = cache.find(levels);
  if (it != cache.end()) return it->second;
  Ladder l;
  l.meshes = refine_uniform(cow(), {}, levels, Backend::Optimized);
  SparseMatrix total;
  for (int k = 0; k < levels; ++k) {
    const SparseMatrix S = make_subdivider(Backend::Optimized)->refine(l.meshes[k], {}).S;
    l.S.emplace_back(S);
    total = k == 0 ? S : SparseMatrix(S * total);
  }
  l.composed = total;
  return cache.emplace(levels, std::move(l)).first->second;
}

void set_counters(benchmark::State& state, int levels) {
  state.counters["fine_vertices"] = static_cast<double>(ladder(levels).meshes.back().n_vertices());
}

void BM_Topology_OpenSubdiv(benchmark::State& state) {
  const int levels = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(osd_refine(levels).get());
  set_counters(state, levels);
}

void BM_Topology_Fairshape(benchmark::State& state) {
  const int levels = static_cast<int>(state.range(0));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(1)));
  for (auto _ : state) {
    SurfaceMesh m = refine_topology(cow(), SchemeType::CatmullClark, CreaseMethod::Uniform);
    for (int l = 1; l < levels; ++l) m = refine_topology(m, SchemeType::CatmullClark, CreaseMethod::Uniform);
    benchmark::DoNotOptimize(m.n_faces());
  }
  set_counters(state, levels);
}

void BM_Primvar_OpenSubdiv(benchmark::State& state) {
  const int levels = static_cast<int>(state.range(0));
  const auto refiner = osd_refine(levels);
  std::vector<OsdVertex> buf(refiner->GetNumVerticesTotal());
  for (int v = 0; v < cow().n_vertices(); ++v)
    for (int k = 0; k < 3; ++k) buf[v].p[k] = cow().positions()(v, k);
  Osd::Far::PrimvarRefinerReal<double> primvar(*refiner);
  for (auto _ : state) {
    OsdVertex* src = buf.data();
    for (int l = 1; l <= levels; ++l) {
      OsdVertex* dst = src + refiner->GetLevel(l - 1).GetNumVertices();
      primvar.Interpolate(l, src, dst);
      src = dst;
    }
    benchmark::DoNotOptimize(src);
  }
  set_counters(state, levels);
}

// Positions through the ladder, one step function per level.
template <class Step>
void run_ladder(benchmark::State& state, const Step& step) {
  const int levels = static_cast<int>(state.range(0));
  const Ladder& l = ladder(levels);
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(1)));
  std::vector<MatrixX3> X(levels + 1);
  X[0] = cow().positions();
  for (auto _ : state) {
    for (int k = 0; k < levels; ++k) step(l, k, X[k], X[k + 1]);
    benchmark::DoNotOptimize(X.back().data());
  }
  set_counters(state, levels);
}

void BM_Primvar_Fairshape(benchmark::State& state) {
  run_ladder(state, [](const Ladder& l, int k, const MatrixX3& x, MatrixX3& y) { apply_stencils(l.S[k], x, y); });
}

// Like OpenSubdiv's PrimvarRefiner: no stored operator, weights derived from topology.
void BM_PrimvarMatrixFree_Fairshape(benchmark::State& state) {
  run_ladder(state, [](const Ladder& l, int k, const MatrixX3& x, MatrixX3& y) {
    subdivide_positions_matrix_free(l.meshes[k], {}, x, y);
  });
}

void BM_Stencils_OpenSubdiv(benchmark::State& state) {
  const int levels = static_cast<int>(state.range(0));
  const auto refiner = osd_refine(levels);
  Osd::Far::StencilTableFactoryReal<double>::Options o;
  o.generateIntermediateLevels = false;
  o.generateOffsets = true;
  std::unique_ptr<const Osd::Far::StencilTableReal<double>> table(
      Osd::Far::StencilTableFactoryReal<double>::Create(*refiner, o));
  std::vector<OsdVertex> src(cow().n_vertices()), dst(table->GetNumStencils());
  for (int v = 0; v < cow().n_vertices(); ++v)
    for (int k = 0; k < 3; ++k) src[v].p[k] = cow().positions()(v, k);
  for (auto _ : state) {
    table->UpdateValues(src.data(), dst.data());
    benchmark::DoNotOptimize(dst.data());
  }
  set_counters(state, levels);
}

void BM_Stencils_Fairshape(benchmark::State& state) {
  const int levels = static_cast<int>(state.range(0));
  const Ladder& l = ladder(levels);
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(1)));
  MatrixX3 Y;
  for (auto _ : state) {
    apply_stencils(l.composed, cow().positions(), Y);
    benchmark::DoNotOptimize(Y.data());
  }
  set_counters(state, levels);
}

void BM_InteractiveDragStep_Fairshape(benchmark::State& state) {
  const int levels = static_cast<int>(state.range(0));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(1)));
  const bench::CowEdit& e = bench::cow_edit(levels, 0);
  const auto make = [](const char* name) {
    return [name] {
      Config none;
      return components().solvers.create(name, Backend::Optimized, none);
    };
  };
  auto finest = make("cholesky")();
  MultilevelEdit edit(e.ladder, Accuracy::Interactive, make("cholesky"), make("gauss_seidel"), *finest, Backend::Optimized);
  double scale = 0;
  for (auto _ : state) {
    scale = scale >= 1 ? 0.1 : scale + 0.1;  // the handle keeps moving
    benchmark::DoNotOptimize(edit.solve(scale).delta.data());
  }
  set_counters(state, levels);
}

void levels_and_threads(benchmark::internal::Benchmark* b) {
  for (int level = 1; level <= 4; ++level)
    for (int threads : {1, 2}) b->Args({level, threads});
}
void levels_only(benchmark::internal::Benchmark* b) {
  for (int level = 1; level <= 4; ++level) b->Args({level, 1});
}

BENCHMARK(BM_Topology_OpenSubdiv)->Apply(levels_only)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Topology_Fairshape)->Apply(levels_and_threads)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Primvar_OpenSubdiv)->Apply(levels_only)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Primvar_Fairshape)->Apply(levels_and_threads)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PrimvarMatrixFree_Fairshape)->Apply(levels_and_threads)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Stencils_OpenSubdiv)->Apply(levels_only)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Stencils_Fairshape)->Apply(levels_and_threads)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InteractiveDragStep_Fairshape)->Args({2, 2})->Args({4, 1})->Args({4, 2})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace fairshape

BENCHMARK_MAIN();
