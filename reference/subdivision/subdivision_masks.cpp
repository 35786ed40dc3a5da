// Reference subdivision: every child vertex's mask written out from the textbook rules
// (Catmull-Clark 1978; Loop 1987; boundary rules of Table 1 in Boier-Martin, Ronfard and
// Bernardini, "Detail-preserving variational surface design with multiresolution
// constraints"; creases and corners as OpenSubdiv: crease_rules.h), visiting the half-edge
// mesh one vertex, edge and face at a time.
#include "fairshape/subdivision/crease_rules.h"
#include "fairshape/subdivision/subdivider.h"

namespace fairshape::reference {
namespace {

using Row = std::vector<std::pair<int, double>>;

void add(Triplets& t, int row, const Row& entries) {
  for (const auto& [col, w] : entries) t.emplace_back(row, col, w);
}

// Face point: the centroid.
Row face_point(const SurfaceMesh& m, int f, double scale) {
  Row r;
  const auto vs = m.face_vertices(f);
  for (int v : vs) r.emplace_back(v, scale / static_cast<double>(vs.size()));
  return r;
}

void append(Row& r, const Row& more, double scale) {
  for (const auto& [col, w] : more) r.emplace_back(col, scale * w);
}

Row smooth_edge_point(const SurfaceMesh& m, int e, const SubdivisionOptions& opt) {
  const int h = 2 * e, a = m.from_vertex(h), b = m.to_vertex(h);
  if (opt.scheme == SchemeType::Loop) {
    const int c = m.to_vertex(m.next(h)), d = m.to_vertex(m.next(m.twin(h)));
    return {{a, 3.0 / 8.0}, {b, 3.0 / 8.0}, {c, 1.0 / 8.0}, {d, 1.0 / 8.0}};
  }
  Row r{{a, 0.25}, {b, 0.25}};  // Catmull-Clark: (a + b + F0 + F1) / 4
  for (int side : {h, m.twin(h)})
    for (const auto& entry : face_point(m, m.face(side), 0.25)) r.push_back(entry);
  return r;
}

// Sharp edges (boundary edges among them) take the midpoint; semi-sharp ones below 1 blend
// midpoint and smooth mask by their sharpness (crease_rules.h).
Row edge_point(const SurfaceMesh& m, int e, const SubdivisionOptions& opt) {
  const int h = 2 * e, a = m.from_vertex(h), b = m.to_vertex(h);
  const double w = edge_crease_weight(m, e, opt.crease);
  if (w == 1.0) return {{a, 0.5}, {b, 0.5}};
  if (w == 0.0) return smooth_edge_point(m, e, opt);
  Row r{{a, 0.5 * w}, {b, 0.5 * w}};
  append(r, smooth_edge_point(m, e, opt), 1.0 - w);
  return r;
}

// The scheme's mask for an interior vertex.
Row smooth_vertex_point(const SurfaceMesh& m, int v, const SubdivisionOptions& opt) {
  const auto ring = m.vertex_neighbors(v);
  const double n = static_cast<double>(ring.size());
  Row r;
  if (opt.scheme == SchemeType::Loop) {
    const double beta = loop_beta(static_cast<int>(ring.size()), opt.weights);
    r.emplace_back(v, 1.0 - n * beta);
    for (int w : ring) r.emplace_back(w, beta);
    return r;
  }
  // Catmull-Clark: (n − 2)/n v + 1/n² Σ edge neighbours + 1/n² Σ face points.
  r.emplace_back(v, (n - 2.0) / n);
  for (int w : ring) r.emplace_back(w, 1.0 / (n * n));
  for (int f : m.vertex_faces(v))
    for (const auto& entry : face_point(m, f, 1.0 / (n * n))) r.push_back(entry);
  return r;
}

// Smooth, crease (a cubic B-spline along the two sharp edges; on the boundary, the boundary
// curve) and corner masks, blended as crease_rules.h decides.
Row vertex_point(const SurfaceMesh& m, int v, const SubdivisionOptions& opt) {
  const VertexMaskBlend b = vertex_mask_blend(m, v, opt.boundary, opt.crease);
  if (b.smooth == 1.0) return smooth_vertex_point(m, v, opt);
  Row r;
  if (b.crease > 0) r = {{v, 0.75 * b.crease}, {b.crease_a, 0.125 * b.crease}, {b.crease_b, 0.125 * b.crease}};
  if (b.corner > 0) r.emplace_back(v, b.corner);
  if (b.smooth > 0) append(r, smooth_vertex_point(m, v, opt), b.smooth);
  return r;
}

class MaskSubdivider : public Subdivider {
 public:
  Refinement refine(const SurfaceMesh& m, const SubdivisionOptions& opt) const override {
    if (opt.scheme == SchemeType::Loop) require_triangles(m, "subdivide");
    const int nv = m.n_vertices(), ne = m.n_edges();
    Triplets t;
    for (int v = 0; v < nv; ++v) add(t, v, vertex_point(m, v, opt));
    for (int e = 0; e < ne; ++e) add(t, nv + e, edge_point(m, e, opt));
    if (opt.scheme == SchemeType::CatmullClark)
      for (int f = 0; f < m.n_faces(); ++f) add(t, nv + ne + f, face_point(m, f, 1.0));
    Refinement r;
    r.S.resize(child_vertex_count(m, opt.scheme), nv);
    r.S.setFromTriplets(t.begin(), t.end());
    return r;
  }
};

}  // namespace

std::unique_ptr<Subdivider> make_mask_subdivider() { return std::make_unique<MaskSubdivider>(); }

}  // namespace fairshape::reference
