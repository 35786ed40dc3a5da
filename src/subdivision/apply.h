// Applying a subdivision operator to positions: a row-parallel product over compressed rows
// (each fine vertex reads only its stencil), the optimized counterpart of S * X.
#pragma once

#include "fairshape/core/types.h"

namespace fairshape {

//! Y = S X with S in compressed-row form; TBB over blocks of rows (deterministic).
void apply_stencils(const RowSparseMatrix& S, const MatrixX3& X, MatrixX3& Y);

}  // namespace fairshape
