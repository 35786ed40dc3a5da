// Point constraints of Boier-Martin et al. §4.2, placed on any level k of a multiresolution
// surface (or on its limit surface) and propagated to the edit level l ≤ k. The deformation
// of level k is the subdivision of level l's, so a constraint on vertex i of level k is the
// linear row  e_iᵀ S_{k-1} ··· S_l ΔP^l = C_i  (with the limit stencil in front for limit
// constraints). One step of that product is exactly Table 1's five masks; the coarser the
// edit level, the wider the row and the region of influence (Figure 1 b vs c).
#pragma once

#include <string>
#include <vector>

#include "constraint/constraint.h"
#include "subdivision/multires_surface.h"

namespace fairshape {

struct LinearConstraints {
  SparseMatrix A;     // m × #vertices of the edit level
  Eigen::MatrixXd C;  // m × 3 targets (deformations)
};

//! \throw InvalidInput for a missing level or vertex, a constraint coarser than the edit level,
//! or two incompatible targets on one vertex (naming both constraints).
LinearConstraints propagate_constraints(const MultiresSurface& h, int edit_level,
                                        const std::vector<PointConstraint>& constraints);

}  // namespace fairshape
