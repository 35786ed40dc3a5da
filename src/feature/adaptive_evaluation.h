// Truly adaptive evaluation of a Loop surface with feature curves (Khodakovsky & Schröder, "Fine
// level feature editing for subdivision surfaces", §2.5): the hierarchy is computed only where
// it is needed, on a sparse Loop hierarchy (sparse_loop.h) whose positions equal the uniform
// hierarchy's. A face of level k is quadrisected when
//  - k < from_level (the coarsest level shown is whole), or
//  - it lies in the support of a feature drawn on a finer level (the curve's neighbourhood
//    radius plus a margin of three of the face's longest edges, for the finer levels' one-rings
//    and the surface's sag), so the feature can be applied on its level, or
//  - one of its edge midpoints leaves the plane of a triangle sharing the edge by more than the
//    threshold (Figure 13): a feature's own flatness_angle_deg within its support from its level
//    on, `surface_angle_deg` everywhere (if set), the smallest where several apply, or
//  - its three edge neighbours are quadrisected (balance);
// and, to keep every kept position exact, the faces around the corners of every quadrisected
// face must be present: where they are not, their parents are marked and the evaluation is run
// again (a few passes; each pass costs as much as the refined region).
// Features are applied on their level's faces with the paper's semantics (the level's control
// points move onto the profile), then finer levels follow; a feature drawn on level l < L
// changes the finer levels through the subdivision stencils, and every face with a corner within
// a ring of a changed vertex is quadrisected, down to L (so what it touches is computed, nothing
// far from it). The finest level is then set as `target` asks (visible_profile.h): the paper's
// drawn-level result, the profile on the finest control points, or at the limit by the
// least-squares fit on the moving vertices and their rings (sparse_visible_profile.h) — after
// checking that every vertex those and the measure (profile_measure.h) read is complete. The output
// keeps the leaves; neighbours differ by at most one level (a quadrisected face has all its
// neighbours on its level), green triangles close the T-junctions (adaptive_mesh.h), and every
// vertex takes its position on the deepest level that holds it.
//
// Restrictions: a plain triangle mesh (no details on finer levels: a hierarchy with details
// would need its nonzero details' support refined as well), no crease or corner tags.
#pragma once

#include <vector>

#include "fairshape/core/backend.h"
#include "fairshape/feature/feature_curve.h"
#include "fairshape/feature/sparse_loop.h"
#include "fairshape/feature/visible_profile.h"
#include "fairshape/subdivision/scheme.h"

namespace fairshape::feature {

struct AdaptiveEvaluationOptions {
  int from_level = 0;              // levels below it are quadrisected everywhere
  double surface_angle_deg = 0;    // flatness threshold everywhere; 0: only features' regions refine
  Backend backend = kFastestBackend;
  //! false: the features only mark their supports (a run places world points on the sparse
  //! levels this makes before the features exist on them).
  bool apply_features = true;
  //! Where the profile is exact (profile_on): what the finest level's positions are.
  ProfileTarget target = ProfileTarget::DrawnLevel;
};

struct AdaptiveEvaluation {
  std::vector<SparseLevel> levels;          // 0..L, the present faces of each (and `original`)
  std::vector<std::vector<char>> split;     // per level and local face: quadrisected
  SurfaceMesh mesh;                         // the leaves, green closure included
  std::vector<UniformId> mesh_vertex;       // uniform id of each output vertex
  std::vector<int> mesh_vertex_level;       // the level its position comes from
  std::vector<int> triangles_per_level;     // output triangles by the level of their leaf
  std::vector<double> feature_angle_deg;    // per feature (input order): its threshold
  //! Per feature (input order) once applied: its base curve, segment faces local to
  //! levels[feature.level] (its patch's faces); and per level the positions before that
  //! level's features moved them (empty where none): what a run measures the profile against.
  std::vector<BaseCurve> curves;
  std::vector<MatrixX3> unperturbed;
  std::vector<int> feature_level;           // per feature (input order): the level it is drawn on
  int vertices_moved = 0;                   // control points the features moved (all levels)
  int passes = 0;                           // evaluations run until every mark was refinable
  long long faces_computed() const;         // present faces, all levels
};

//! `features` carry points on the uniform faces of their level (as FeaturedSurface takes them).
//! \throw InvalidInput for a non-Loop scheme, tagged creases, levels < 0, from_level outside
//! 0..levels, an angle outside [0, 90), or a feature whose level is outside 0..levels; the
//! errors of build_base_curve / compute_perturbation for a feature that cannot be applied.
AdaptiveEvaluation evaluate_adaptive(const SurfaceMesh& base, const SubdivisionOptions& opt, int levels,
                                     const std::vector<FeatureCurve>& features,
                                     const AdaptiveEvaluationOptions& options);

}  // namespace fairshape::feature
