// The freedom the paper's split leaves unused (Boier-Martin et al. §4.3). The split fixes every
// unknown a constraint row reaches at the minimum-norm (or nearest) values of its rows and
// optimizes only the rest. Where the rows pin those unknowns outright (positions, fixed regions)
// that is the optimum; where they leave them room — a normal constraint's two tangent rows over a
// vertex's ring — the split's answer is not the minimizer of the same problem
// (papers/boier-martin/README.md, "One reference per problem"). This finds that room: the
// directions the constrained unknowns can move without changing any row.
#pragma once

#include <vector>

#include "fairshape/core/types.h"

namespace fairshape {

struct ConstrainedFreedom {
  std::vector<int> columns;  // the unknowns rows reach but no single-entry row pins
  Eigen::MatrixXd basis;     // columns.size() × d, orthonormal: the null space of those rows there
};

//! Unknowns that some row with one entry pins are left out (they cannot move); the null space of
//! the remaining rows restricted to the remaining reached unknowns, by an SVD (rank cut at 1e-10
//! of the largest singular value). Empty when more than `max_columns` unknowns remain (the dense
//! SVD would cost more than the solve it corrects).
ConstrainedFreedom constrained_freedom(const SparseMatrix& A, int max_columns);

}  // namespace fairshape
