// Child connectivity of one subdivision step, built straight from the parent's half-edges
// (every child index is known in closed form), in parallel, with no hashing. Produces the
// same faces, in the same order and starting corner, as child_faces().
//
// Child edges: parent edge e splits into child edges 2e (from the half-edge 2e's origin to
// the edge point) and 2e + 1 (edge point to its end); then each face adds one interior edge
// per corner (Catmull-Clark: edge point -> face point; Loop: edge point -> previous edge point).
// Both back ends use it: without TBB (FAIRSHAPE_WITH_TBB=0) the loops run serially.
#include "fairshape/core/backend.h"
#if FAIRSHAPE_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#endif

#include "fairshape/subdivision/crease_rules.h"
#include "fairshape/subdivision/subdivider.h"

namespace fairshape {
namespace {

// The child half-edges covering the first and second half of parent half-edge h.
inline int first_half(int h) { const int e = h >> 1, s = h & 1; return 2 * (2 * e + s) + s; }
inline int second_half(int h) { const int e = h >> 1, s = h & 1; return 2 * (2 * e + 1 - s) + s; }

template <class F>
void parallel_range(int n, const F& body) {
#if FAIRSHAPE_WITH_TBB
  tbb::parallel_for(tbb::blocked_range<int>(0, n, 2048), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(); i != r.end(); ++i) body(i);
  });
#else
  for (int i = 0; i < n; ++i) body(i);
#endif
}

}  // namespace

SurfaceMesh refine_topology(const SurfaceMesh& m, SchemeType scheme, CreaseMethod crease) {
  const int nv = m.n_vertices(), ne = m.n_edges(), nf = m.n_faces(), nh = m.n_halfedges();
  const bool cc = scheme == SchemeType::CatmullClark;
  if (!cc) require_triangles(m, "subdivide");
  // First corner (= first child face, = first interior edge) of every face.
  std::vector<int> corner(nf + 1, 0);
  for (int f = 0; f < nf; ++f) corner[f + 1] = corner[f] + (cc ? m.face_size(f) : 3);
  const int child_edges = 2 * ne + corner[nf];
  const int child_faces = cc ? corner[nf] : 4 * nf;
  SurfaceMesh::HalfedgeArrays a;
  a.to_vertex.assign(2 * child_edges, -1);
  a.next.assign(2 * child_edges, -1);
  a.prev.assign(2 * child_edges, -1);
  a.face.assign(2 * child_edges, -1);
  a.vertex_halfedge.assign(child_vertex_count(m, scheme), -1);
  a.face_halfedge.assign(child_faces, -1);
  auto edge_point = [nv](int h) { return nv + (h >> 1); };

  parallel_range(nh, [&](int h) {  // the two halves of every parent half-edge
    a.to_vertex[first_half(h)] = edge_point(h);
    a.to_vertex[second_half(h)] = m.to_vertex(h);
    if (m.is_boundary_halfedge(h)) {  // boundary loops stay loops
      a.next[first_half(h)] = second_half(h);
      a.next[second_half(h)] = first_half(m.next(h));
    }
  });
  parallel_range(nf, [&](int f) {
    int hs[64];
    std::vector<int> big;
    const int k = corner[f + 1] - corner[f];
    int* h = k <= 64 ? hs : (big.resize(k), big.data());
    h[0] = m.face_halfedge(f);
    for (int i = 1; i < k; ++i) h[i] = m.next(h[i - 1]);
    auto link = [&](int child_face, std::initializer_list<int> loop) {
      const int* c = loop.begin();
      const int n = static_cast<int>(loop.size());
      for (int j = 0; j < n; ++j) {
        a.next[c[j]] = c[(j + 1) % n];
        a.face[c[j]] = child_face;
      }
      a.face_halfedge[child_face] = c[0];
    };
    const int interior = 2 * (2 * ne + corner[f]);  // first interior half-edge of this face
    if (cc) {
      const int face_point = nv + ne + f;
      for (int i = 0; i < k; ++i) {
        const int p = (i + k - 1) % k;
        a.to_vertex[interior + 2 * i] = face_point;               // edge point -> face point
        a.to_vertex[interior + 2 * i + 1] = edge_point(h[i]);      // face point -> edge point
        link(corner[f] + i, {first_half(h[i]), interior + 2 * i, interior + 2 * p + 1, second_half(h[p])});
      }
      return;
    }
    for (int i = 0; i < 3; ++i) {  // interior edge i: E(h_i) -> E(h_{i-1})
      const int p = (i + 2) % 3;
      a.to_vertex[interior + 2 * i] = edge_point(h[p]);
      a.to_vertex[interior + 2 * i + 1] = edge_point(h[i]);
    }
    const int f4 = 4 * f;
    link(f4 + 0, {first_half(h[0]), interior + 0, second_half(h[2])});                // a, ab, ca
    link(f4 + 1, {second_half(h[0]), first_half(h[1]), interior + 2});                // ab, b, bc
    link(f4 + 2, {interior + 4, second_half(h[1]), first_half(h[2])});                // ca, bc, c
    link(f4 + 3, {interior + 3, interior + 5, interior + 1});                          // ab, bc, ca
  });
  parallel_range(2 * child_edges, [&](int h) { a.prev[a.next[h]] = h; });
  // Outgoing half-edges, the boundary one where there is one (as SurfaceMesh requires).
  parallel_range(nv, [&](int v) {
    if (!m.is_isolated(v)) a.vertex_halfedge[v] = first_half(m.halfedge(v));
  });
  parallel_range(ne, [&](int e) {
    a.vertex_halfedge[nv + e] = m.is_boundary_halfedge(2 * e + 1) ? second_half(2 * e + 1) : second_half(2 * e);
  });
  if (cc) parallel_range(nf, [&](int f) { a.vertex_halfedge[nv + ne + f] = 2 * (2 * ne + corner[f]) + 1; });
  SurfaceMesh fine = SurfaceMesh::from_halfedge_arrays(MatrixX3::Zero(child_vertex_count(m, scheme), 3), std::move(a));
  child_sharpness(m, fine, crease);  // crease and corner tags decay into the child
  return fine;
}

}  // namespace fairshape
