// One subdivision step of positions without a stored operator, staged as the rules are:
// face points, then edge points (which use them), then vertex points (which use both), each
// stage a TBB loop whose outputs are independent. Same arithmetic as the masks, so the result
// equals S X up to rounding.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "fairshape/subdivision/crease_rules.h"
#include "fairshape/subdivision/subdivider.h"

namespace fairshape {
namespace {

template <class F>
void parallel_range(int n, const F& body) {
  tbb::parallel_for(tbb::blocked_range<int>(0, n, 2048), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(); i != r.end(); ++i) body(i);
  });
}

using Row = Eigen::RowVector3d;

}  // namespace

void subdivide_positions_matrix_free(const SurfaceMesh& m, const SubdivisionOptions& opt, const MatrixX3& X,
                                     MatrixX3& Y) {
  const bool cc = opt.scheme == SchemeType::CatmullClark;
  if (!cc) require_triangles(m, "subdivide");
  const int nv = m.n_vertices(), ne = m.n_edges(), nf = m.n_faces();
  Y.resize(child_vertex_count(m, opt.scheme), 3);
  const int fp = nv + ne;  // first face point
  if (cc) {
    parallel_range(nf, [&](int f) {
      const int h0 = m.face_halfedge(f);
      Row sum = Row::Zero();
      int k = 0, h = h0;
      do { sum += X.row(m.from_vertex(h)); ++k; h = m.next(h); } while (h != h0);
      Y.row(fp + f) = sum / k;
    });
  }
  // Creases and corners (the boundary among them) as crease_rules.h: a semi-sharp edge below 1
  // blends midpoint and smooth rule, a vertex whose rule changes blends the two rules' points.
  const bool tagged = m.has_sharpness();
  parallel_range(ne, [&](int e) {
    const int h = 2 * e, t = h ^ 1;
    const Row a = X.row(m.from_vertex(h)), b = X.row(m.to_vertex(h));
    const double w = tagged ? edge_crease_weight(m, e, opt.crease) : (m.is_boundary_edge(e) ? 1.0 : 0.0);
    Row smooth;
    if (w == 1.0) { Y.row(nv + e) = 0.5 * (a + b); return; }
    if (cc) smooth = 0.25 * (a + b + Y.row(fp + m.face(h)) + Y.row(fp + m.face(t)));
    else smooth = 0.375 * (a + b) + 0.125 * (X.row(m.to_vertex(m.next(h))) + X.row(m.to_vertex(m.next(t))));
    Y.row(nv + e) = w == 0.0 ? smooth : Row(w * 0.5 * (a + b) + (1.0 - w) * smooth);
  });
  parallel_range(nv, [&](int v) {
    const int h0 = m.halfedge(v);
    const Row x = X.row(v);
    if (h0 < 0) { Y.row(v) = x; return; }
    if (!tagged && m.is_boundary_halfedge(h0)) {
      const bool corner = m.rotate_ccw(m.rotate_ccw(h0)) == h0;  // valence 2: one face
      Y.row(v) = corner && opt.boundary == BoundaryMode::EdgeAndCorner
                     ? x
                     : Row(0.75 * x + 0.125 * (X.row(m.to_vertex(h0)) + X.row(m.from_vertex(m.prev(h0)))));
      return;
    }
    VertexMaskBlend blend;
    blend.smooth = 1.0;
    if (tagged) blend = vertex_mask_blend(m, v, opt.boundary, opt.crease);
    Row sharp = Row::Zero();
    if (blend.crease > 0.0) sharp += blend.crease * (0.75 * x + 0.125 * (X.row(blend.crease_a) + X.row(blend.crease_b)));
    if (blend.corner > 0.0) sharp += blend.corner * x;
    if (blend.smooth == 0.0) { Y.row(v) = sharp; return; }
    Row ring = Row::Zero(), faces = Row::Zero();
    int n = 0, h = h0;
    do {
      ring += X.row(m.to_vertex(h));
      if (cc) faces += Y.row(fp + m.face(h));
      ++n;
      h = m.rotate_ccw(h);
    } while (h != h0);
    Row smooth;
    if (cc) {
      smooth = (n - 2.0) / n * x + (ring + faces) / (double(n) * n);
    } else {
      const double beta = loop_beta(n, opt.weights);
      smooth = (1.0 - n * beta) * x + beta * ring;
    }
    Y.row(v) = blend.smooth == 1.0 ? smooth : Row(sharp + blend.smooth * smooth);
  });
}

}  // namespace fairshape
