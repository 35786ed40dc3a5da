// The analysis step of a multiresolution surface: the coarse control points c whose
// subdivision S c is nearest the finer points X in least squares, min ‖S c − X‖_F (the
// details are then X − S c). Boier-Martin, Ronfard, Bernardini, "Detail-preserving variational
// surface design with multiresolution constraints", §3.
#pragma once

#include "fairshape/core/backend.h"
#include "fairshape/core/types.h"

namespace fairshape {

//! The least-squares coarse points of X (n_fine × 3) under S (n_fine × n_coarse, full column
//! rank). Reference: the normal equations SᵀS c = SᵀX factored (the plain statement).
//! Optimized: conjugate gradients on the normal equations, never forming or factoring SᵀS
//! (detail_fit.cpp says why that is enough).
//! An iteration that does not reach its tolerance falls back to the factorization.
//! \throw InvalidInput when SᵀS is singular (a coarse vertex with no finer point).
MatrixX3 fit_coarse_points(const SparseMatrix& S, const MatrixX3& X, Backend backend);

}  // namespace fairshape
