// One uniform subdivision step as a sparse linear operator: the fine mesh's vertex positions
// are S · (coarse positions). Child vertices are numbered so that ids nest across levels:
//   [0, #V)                 vertex points (a vertex keeps its id),
//   [#V, #V + #E)           edge points (edge e -> #V + e),
//   [#V + #E, ... + #F)     face points (Catmull-Clark only, face f -> #V + #E + f).
// Child faces: Catmull-Clark splits a k-gon into k quads (corner i: v_i, edge i, face, edge i-1);
// Loop splits a triangle into four (three corners, then the middle one).
// Edge ids of a refined mesh follow refine_topology (the halves of parent edge e are 2e and
// 2e + 1, then one interior edge per face corner), so refining level by level gives the same
// ids every time. A mesh re-read from a file numbers its edges by first appearance instead:
// refining it again numbers the new edge points differently (positions are the same).
#pragma once

#include <memory>

#include "fairshape/core/backend.h"
#include "fairshape/mesh/surface_mesh.h"
#include "fairshape/subdivision/scheme.h"

namespace fairshape {

struct Refinement {
  SparseMatrix S;  // #fine × #coarse, rows sum to 1 (the fine connectivity: refine_topology)
};

class Subdivider {
 public:
  virtual ~Subdivider() = default;
  //! \throw InvalidInput for Loop on a mesh that is not all triangles.
  virtual Refinement refine(const SurfaceMesh& coarse, const SubdivisionOptions& opt) const = 0;
};

//! Reference: masks applied vertex by vertex on the half-edge mesh, triplets, setFromTriplets.
//! Optimized: stencil rows built in parallel (TBB) straight into compressed storage.
//! Defined in make_subdivider.cpp, above both back ends.
std::unique_ptr<Subdivider> make_subdivider(Backend backend);

//! One step of positions without storing S: every stencil is generated and applied on the fly
//! (TBB over child vertices). Restriction by Sᵀ uses the stored operator instead.
void subdivide_positions_matrix_free(const SurfaceMesh& coarse, const SubdivisionOptions& opt, const MatrixX3& X,
                                     MatrixX3& Y);

//! Vertices whose valence differs from the scheme's regular one (Catmull-Clark: 4 inside, 3 on
//! a boundary; Loop: 6 and 4) or that touch a polygon the scheme does not produce (a triangle
//! for Catmull-Clark): where subdivision reproduces only linear functions.
std::vector<int> extraordinary_vertices(const SurfaceMesh& mesh, SchemeType scheme);

//! The child faces, written out plainly: the specification refine_topology is tested against.
PolygonList child_faces(const SurfaceMesh& coarse, SchemeType scheme);
int child_vertex_count(const SurfaceMesh& coarse, SchemeType scheme);
//! The fine mesh's connectivity (positions zero), built directly from the parent's half-edges
//! in parallel; polygons() equals child_faces(). Crease and corner sharpness decays into it by
//! `crease` (crease_rules.h).
SurfaceMesh refine_topology(const SurfaceMesh& coarse, SchemeType scheme, CreaseMethod crease);
void require_triangles(const SurfaceMesh& mesh, const char* who);  // throws InvalidInput

//! One step, positions included. \throw InvalidInput as refine().
SurfaceMesh subdivide_once(const SurfaceMesh& coarse, const SubdivisionOptions& opt, Backend backend,
                           SparseMatrix* S = nullptr);

//! Estimated peak memory of `levels` steps (bytes); refine_uniform refuses beyond a limit.
double estimated_subdivision_bytes(const SurfaceMesh& coarse, SchemeType scheme, int levels);
struct UniformRefineLimits {
  int max_levels = 12;
  double max_bytes = 8.0 * (1ull << 30);  // 8 GiB
};
//! `levels` uniform steps; `operators` (optional) receives S_0 .. S_{levels-1}.
//! \throw InvalidInput for levels < 1 or > max_levels, or when the estimate exceeds
//! max_bytes (the message gives the estimate).
std::vector<SurfaceMesh> refine_uniform(const SurfaceMesh& base, const SubdivisionOptions& opt, int levels,
                                        Backend backend, const UniformRefineLimits& limits = {},
                                        std::vector<SparseMatrix>* operators = nullptr);

}  // namespace fairshape
