// Point constraints of Boier-Martin et al. §4.2, placed on any level k of a multiresolution
// surface (or on its limit surface) and propagated to the edit level l ≤ k. The deformation
// of level k is the subdivision of level l's, so a constraint on vertex i of level k is the
// linear row  e_iᵀ S_{k-1} ··· S_l ΔP^l = C_i  (with the limit stencil in front for limit
// constraints). One step of that product is exactly Table 1's five masks; the coarser the
// edit level, the wider the row and the region of influence (Figure 1 b vs c).
// A normal constraint at vertex i of level k gives the two rows of §4.2,
//   Σ_j D_{r,j} (ΔP_j − ΔP_i)·N = −Σ_j D_{r,j} (P_j − P_i)·N,   r = u, v,
// with D the divided differences of level k's rest shape; they mix x, y and z, so they live
// on the stacked unknowns [Δx; Δy; Δz] (§5 "Point vs. normal constraints").
#pragma once

#include <string>
#include <vector>

#include "fairshape/constraint/constraint.h"
#include "fairshape/subdivision/multires_surface.h"

namespace fairshape {

struct LinearConstraints {
  SparseMatrix A;     // m × n (n = #vertices of the edit level), shared by x, y, z
  Eigen::MatrixXd C;  // m × 3 targets (deformations)
  SparseMatrix A_coupled;     // q × 3n rows on [Δx; Δy; Δz] (normal constraints)
  Eigen::VectorXd C_coupled;  // q
  bool coupled() const { return A_coupled.rows() > 0; }
};

//! \throw InvalidInput for a missing level or vertex, a constraint coarser than the edit level,
//! or two incompatible targets or normals on one vertex (naming both constraints).
//! `current` (optional, a shape of the same hierarchy): the targets become what is still
//! missing from it — the offset minus how far the constrained point has already moved, the
//! normal rows' right-hand side measured on its tangents — so a later pass of a regional edit
//! (design/regional_edit.h) adds what earlier passes left.
LinearConstraints propagate_constraints(const MultiresSurface& h, int edit_level, const DesignConstraints& constraints,
                                        const MultiresSurface* current = nullptr);
LinearConstraints propagate_constraints(const MultiresSurface& h, int edit_level,
                                        const std::vector<PointConstraint>& points,
                                        const MultiresSurface* current = nullptr);

//! The targets propagate_constraints(h, l, constraints, &current) gives, in the same row order,
//! without the rows (C and C_coupled only): what is still missing from `current`.
LinearConstraints missing_targets(const MultiresSurface& h, const DesignConstraints& constraints,
                                  const MultiresSurface& current);

//! The row of propagate_constraints' A (and C) that each of `points` makes, index for index:
//! points on one vertex with the same target share a row. \throw InvalidInput as propagate_constraints.
std::vector<int> point_rows(const MultiresSurface& h, int edit_level, const std::vector<PointConstraint>& points);

//! The checks of propagate_constraints that build no row (the levels and vertices exist, the
//! targets and normals are finite, no two on one vertex conflict) and require_fixed_position:
//! cheap, for validating a sweep. \throw InvalidInput as they would.
void check_constraints(const MultiresSurface& h, int edit_level, const DesignConstraints& constraints);

//! \throw InvalidInput when no row fixes a position: the energies are translation invariant,
//! so the deformation would be undetermined.
void require_fixed_position(const LinearConstraints& constraints);

//! The normal estimated at `vertex` by the divided differences of `D_mesh` (its rest shape)
//! applied to `positions`: Q_u × Q_v normalized — what a normal constraint prescribes.
Vec3 estimated_normal(const SurfaceMesh& D_mesh, const MatrixX3& positions, int vertex);

//! The unit normal that normal constraint `nc`'s rows see at `positions` of its level (`mesh`
//! at rest): Q_u × Q_v of its tangents (a surface point's ∂S/∂u × ∂S/∂v), oriented like the
//! faces around it at rest — so a result that met the rows with the reverse of the target
//! shows a normal opposite to it. Zero where the tangents are parallel.
Vec3 achieved_normal(const SurfaceMesh& mesh, const MatrixX3& positions, const NormalConstraint& nc);

}  // namespace fairshape
