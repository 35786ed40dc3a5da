#include "fairshape/subdivision/subdivider.h"

#include <cmath>
#include <sstream>

#include "fairshape/core/error.h"
#include "fairshape/subdivision/apply.h"

namespace fairshape {

SurfaceMesh subdivide_once(const SurfaceMesh& coarse, const SubdivisionOptions& opt, Backend backend,
                           SparseMatrix* S_out) {
  // Connectivity is shared bookkeeping (so vertex ids agree across back ends); the
  // arithmetic, S and its application, is each back end's own. The optimized back end
  // builds no operator unless the caller wants it.
  require_backend(backend);
  SurfaceMesh fine = refine_topology(coarse, opt.scheme, opt.crease);
#if FAIRSHAPE_WITH_TBB
  if (backend == Backend::Optimized && !S_out) {
    subdivide_positions_matrix_free(coarse, opt, coarse.positions(), fine.positions());
    return fine;
  }
#endif
  Refinement r = make_subdivider(backend)->refine(coarse, opt);
#if FAIRSHAPE_WITH_TBB
  if (backend == Backend::Optimized) apply_stencils(r.S, coarse.positions(), fine.positions());
  else fine.positions() = r.S * coarse.positions();
#else
  fine.positions() = r.S * coarse.positions();
#endif
  if (S_out) *S_out = std::move(r.S);
  return fine;
}

double estimated_subdivision_bytes(const SurfaceMesh& coarse, SchemeType scheme, int levels) {
  // Each step multiplies faces by ~4 (a k-gon gives k quads); per fine vertex the stored data
  // (positions, half-edges, the operator S) is about 400 bytes, summed over all levels.
  double faces = 0;
  for (int f = 0; f < coarse.n_faces(); ++f) faces += scheme == SchemeType::Loop ? 4 : coarse.face_size(f);
  double total = 0, level_faces = faces;
  for (int l = 1; l <= levels; ++l, level_faces *= 4) total += level_faces * 400.0;
  return total;
}

std::vector<SurfaceMesh> refine_uniform(const SurfaceMesh& base, const SubdivisionOptions& opt, int levels,
                                        Backend backend, const UniformRefineLimits& limits,
                                        std::vector<SparseMatrix>* operators) {
  if (levels < 1 || levels > limits.max_levels)
    throw InvalidInput("levels must be in [1, " + std::to_string(limits.max_levels) + "], got " +
                       std::to_string(levels));
  const double bytes = estimated_subdivision_bytes(base, opt.scheme, levels);
  if (bytes > limits.max_bytes) {
    std::ostringstream os;
    os.precision(3);
    os << levels << " levels of " << to_string(opt.scheme) << " on " << base.n_faces() << " faces need about "
       << bytes / (1 << 30) << " GiB, over the limit of " << limits.max_bytes / (1 << 30)
       << " GiB (raise it: `fairshape subdivide --max-memory-gb`, or input.max_memory_gb in a surface-edit config)";
    throw InvalidInput(os.str());
  }
  if (opt.scheme == SchemeType::Loop) require_triangles(base, "subdivide");
  std::vector<SurfaceMesh> out{base};
  if (operators) operators->resize(levels);
  for (int l = 0; l < levels; ++l)
    out.push_back(subdivide_once(out.back(), opt, backend, operators ? &(*operators)[l] : nullptr));
  return out;
}

std::vector<int> extraordinary_vertices(const SurfaceMesh& mesh, SchemeType scheme) {
  const int regular_face = scheme == SchemeType::CatmullClark ? 4 : 3;
  const int interior = scheme == SchemeType::CatmullClark ? 4 : 6, boundary = scheme == SchemeType::CatmullClark ? 3 : 4;
  std::vector<int> out;
  for (int v = 0; v < mesh.n_vertices(); ++v) {
    if (mesh.is_isolated(v)) continue;
    bool irregular = mesh.valence(v) != (mesh.is_boundary_vertex(v) ? boundary : interior);
    for (int h : mesh.outgoing_halfedges(v))
      if (!mesh.is_boundary_halfedge(h) && mesh.face_size(mesh.face(h)) != regular_face) irregular = true;
    if (irregular) out.push_back(v);
  }
  return out;
}

}  // namespace fairshape
