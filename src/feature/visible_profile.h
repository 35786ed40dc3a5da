// The profile where it is seen: Khodakovsky & Schröder ("Fine level feature editing
// for subdivision surfaces", §1.4, §2.5) move the control points of the level l a curve is drawn
// on; subdividing them smooths the profile (a groove drawn on level 0 of the helmet reaches 59 %
// of its height on the finest level). Here level l keeps that role in the hierarchy (coarse
// levels show the feature, finer features ride on it, the curve is split and its distances are
// unrolled on level l), and the finest level is then set so that the visible surface carries the
// profile exactly as a displacement: the finest control points (ProfileTarget::Finest), or the
// limit points of the finest vertices, found by a sparse least-squares solve for the finest
// control points (ProfileTarget::Limit).
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "fairshape/core/name_table.h"
#include "fairshape/feature/perturbation.h"
#include "fairshape/subdivision/scheme.h"

namespace fairshape::feature {

enum class ProfileTarget {
  DrawnLevel,  // the paper read literally: only the drawn level's control points follow the profile
  Finest,      // the finest level's control points carry the profile
  Limit        // the limit surface at the finest vertices carries it
};
const NameTable<ProfileTarget>& profile_target_names();

//! One level's features as the operator that applied them there: the level's mesh before they
//! moved it (the curves are attached to it), its normals and the base curves.
struct LevelOperator {
  int level = 0;
  std::vector<int> ids;  // feature ids, in the order of `curves`
  // Not const: a region re-evaluation (FeaturedSurface) updates them where a coarser level moved.
  std::shared_ptr<SurfaceMesh> mesh;
  std::shared_ptr<TriangleSurface> surface;
  std::vector<BaseCurve> curves;
};

//! The visible targets, level by level: fine[k] (limit[k]) are the finest control points (their
//! limit points) with the operators before k applied; back() has them all.
struct VisibleTargets {
  std::vector<MatrixX3> fine, limit;
  SparseMatrix limit_matrix;  // finest control points -> limit points of the finest vertices
  Eigen::SparseMatrix<double, Eigen::RowMajor> limit_by_rows;  // the same by rows (the fit reads rows)
};

//! Applies the operators in order (coarse levels first, as the hierarchy does) as displacements
//! of the original finest level's control points and of its limit points.
VisibleTargets compose_visible_targets(const SurfaceMesh& finest_original, const SubdivisionOptions& opt,
                                       const std::vector<LevelOperator>& operators, Backend backend);

//! Control points X = reference + C whose limit points move by `limit_displacement`: C is the
//! least-squares solution of L C = limit_displacement, nonzero only on the vertices whose limit
//! point moves plus `rings` rings (exactly zero elsewhere, so nothing far moves by rounding) (the limit stencil is a one-ring: the rows are
//! those vertices plus one more ring). \throw SolverError when the solve fails.
MatrixX3 control_points_for_limit(const SurfaceMesh& mesh, const SparseMatrix& limit_matrix, const MatrixX3& reference,
                                  const MatrixX3& limit_displacement, int rings = 2);

//! The limit displacement of a finest vertex, row by row (a step reads only its region).
using LimitDisplacement = std::function<Vec3(int)>;

//! control_points_for_limit after a design step changed `limit_displacement` only on the rows
//! `changed`: X (the previous fit) is re-solved on the blocks of the fit those rows meet (the
//! fit separates into blocks of moving vertices more than 2 rings + 2 apart: their unknowns
//! share no row) and kept elsewhere. `was_moving`: per vertex, a nonzero limit displacement
//! before the step. Returns the rows of X rewritten. The same X as control_points_for_limit
//! gives (to rounding: the blocks are solved apart). \throw SolverError when the solve fails.
std::vector<int> refit_control_points_for_limit(const SurfaceMesh& mesh,
                                                const Eigen::SparseMatrix<double, Eigen::RowMajor>& limit_by_rows,
                                                const MatrixX3& reference, const LimitDisplacement& limit_displacement,
                                                const std::vector<char>& was_moving, const std::vector<int>& changed,
                                                MatrixX3& X, int rings = 2);

}  // namespace fairshape::feature
