// Optimized subdivision operator: the same rules as reference/subdivision, with stencil rows
// built in parallel chunks (TBB) straight into compressed row storage, walking half-edges
// without per-vertex allocation. Duplicate columns within a row (a coarse vertex reached
// through several faces) are merged in the row.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>

#include "fairshape/subdivision/crease_rules.h"
#include "fairshape/subdivision/subdivider.h"

namespace fairshape {
namespace {

using Entry = std::pair<int, double>;

class RowBuilder {
 public:
  RowBuilder(const SurfaceMesh& m, const SubdivisionOptions& opt) : m_(m), opt_(opt) {}

  // Appends the merged stencil of child vertex `row` to `out`.
  void build(int row, std::vector<Entry>& out) {
    scratch_.clear();
    const int nv = m_.n_vertices(), ne = m_.n_edges();
    if (row < nv) vertex_point(row);
    else if (row < nv + ne) edge_point(row - nv);
    else face_point(row - nv - ne, 1.0);
    std::sort(scratch_.begin(), scratch_.end(), [](const Entry& a, const Entry& b) { return a.first < b.first; });
    for (const auto& e : scratch_) {
      if (!out.empty() && out.back().first == e.first && merging_) out.back().second += e.second;
      else out.push_back(e);
      merging_ = true;
    }
    merging_ = false;
  }

 private:
  void face_point(int f, double scale) {
    const int h0 = m_.face_halfedge(f);
    int k = 0, h = h0;
    do { ++k; h = m_.next(h); } while (h != h0);
    const double w = scale / k;
    do { scratch_.emplace_back(m_.from_vertex(h), w); h = m_.next(h); } while (h != h0);
  }

  // Sharp edges (the boundary among them) take the midpoint, smooth ones the scheme's mask,
  // semi-sharp ones below 1 a blend by their sharpness (crease_rules.h).
  void edge_point(int e) {
    const int h = 2 * e, t = h ^ 1, a = m_.from_vertex(h), b = m_.to_vertex(h);
    const double w = edge_crease_weight(m_, e, opt_.crease);
    if (w == 1.0) {
      scratch_.insert(scratch_.end(), {{a, 0.5}, {b, 0.5}});
      return;
    }
    if (w > 0.0) scratch_.insert(scratch_.end(), {{a, 0.5 * w}, {b, 0.5 * w}});
    const double s = 1.0 - w;
    if (opt_.scheme == SchemeType::Loop) {
      scratch_.insert(scratch_.end(), {{a, s * 0.375}, {b, s * 0.375}, {m_.to_vertex(m_.next(h)), s * 0.125},
                                       {m_.to_vertex(m_.next(t)), s * 0.125}});
    } else {
      scratch_.insert(scratch_.end(), {{a, s * 0.25}, {b, s * 0.25}});
      face_point(m_.face(h), s * 0.25);
      face_point(m_.face(t), s * 0.25);
    }
  }

  // Smooth, crease and corner masks blended as crease_rules.h decides; an untagged interior
  // vertex is smooth, a boundary vertex a crease along the boundary (or a pinned corner).
  void vertex_point(int v) {
    const int h0 = m_.halfedge(v);
    if (h0 < 0) { scratch_.emplace_back(v, 1.0); return; }
    const VertexMaskBlend blend = vertex_mask_blend(m_, v, opt_.boundary, opt_.crease);
    if (blend.crease > 0.0)
      scratch_.insert(scratch_.end(), {{v, 0.75 * blend.crease}, {blend.crease_a, 0.125 * blend.crease},
                                       {blend.crease_b, 0.125 * blend.crease}});
    if (blend.corner > 0.0) scratch_.emplace_back(v, blend.corner);
    if (blend.smooth > 0.0) smooth_vertex_point(v, blend.smooth);
  }

  void smooth_vertex_point(int v, double scale) {
    const int h0 = m_.halfedge(v);
    int n = 0, h = h0;
    do { ++n; h = m_.rotate_ccw(h); } while (h != h0);
    const double dn = n;
    if (opt_.scheme == SchemeType::Loop) {
      const double beta = loop_beta(n, opt_.weights);
      scratch_.emplace_back(v, scale * (1.0 - dn * beta));
      do { scratch_.emplace_back(m_.to_vertex(h), scale * beta); h = m_.rotate_ccw(h); } while (h != h0);
      return;
    }
    scratch_.emplace_back(v, scale * ((dn - 2.0) / dn));
    do {
      scratch_.emplace_back(m_.to_vertex(h), scale * (1.0 / (dn * dn)));
      face_point(m_.face(h), scale * (1.0 / (dn * dn)));
      h = m_.rotate_ccw(h);
    } while (h != h0);
  }

  const SurfaceMesh& m_;
  const SubdivisionOptions& opt_;
  std::vector<Entry> scratch_;
  bool merging_ = false;
};

class ParallelStencilSubdivider : public Subdivider {
 public:
  Refinement refine(const SurfaceMesh& m, const SubdivisionOptions& opt) const override {
    if (opt.scheme == SchemeType::Loop) require_triangles(m, "subdivide");
    const int rows = child_vertex_count(m, opt.scheme);
    constexpr int kChunk = 4096;
    const int chunks = (rows + kChunk - 1) / kChunk;
    std::vector<std::vector<Entry>> entries(chunks);
    std::vector<std::vector<int>> row_sizes(chunks);
    tbb::parallel_for(tbb::blocked_range<int>(0, chunks, 1), [&](const tbb::blocked_range<int>& r) {
      RowBuilder builder(m, opt);
      for (int c = r.begin(); c != r.end(); ++c)
        for (int row = c * kChunk; row < std::min(rows, (c + 1) * kChunk); ++row) {
          const std::size_t before = entries[c].size();
          builder.build(row, entries[c]);
          row_sizes[c].push_back(static_cast<int>(entries[c].size() - before));
        }
    }, tbb::static_partitioner());

    std::vector<std::size_t> chunk_start(chunks + 1, 0);
    for (int c = 0; c < chunks; ++c) chunk_start[c + 1] = chunk_start[c] + entries[c].size();
    Eigen::SparseMatrix<double, Eigen::RowMajor> R(rows, m.n_vertices());
    R.resizeNonZeros(static_cast<Eigen::Index>(chunk_start[chunks]));
    tbb::parallel_for(tbb::blocked_range<int>(0, chunks, 1), [&](const tbb::blocked_range<int>& r) {
      for (int c = r.begin(); c != r.end(); ++c) {
        std::size_t k = chunk_start[c];
        int row = c * kChunk;
        for (int size : row_sizes[c]) {
          R.outerIndexPtr()[row++] = static_cast<int>(k);
          k += static_cast<std::size_t>(size);
        }
        for (std::size_t i = 0; i < entries[c].size(); ++i) {
          R.innerIndexPtr()[chunk_start[c] + i] = entries[c][i].first;
          R.valuePtr()[chunk_start[c] + i] = entries[c][i].second;
        }
      }
    });
    R.outerIndexPtr()[rows] = static_cast<int>(chunk_start[chunks]);
    Refinement out;
    out.S = R;
    return out;
  }
};

}  // namespace

std::unique_ptr<Subdivider> make_parallel_subdivider() { return std::make_unique<ParallelStencilSubdivider>(); }

}  // namespace fairshape
