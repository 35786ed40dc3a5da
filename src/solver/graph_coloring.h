// Greedy colouring of the adjacency graph of a sparse symmetric matrix: rows of one colour
// share no off-diagonal entry, so a Gauss-Seidel sweep may update them in parallel.
#pragma once

#include <vector>

#include "fairshape/core/types.h"

namespace fairshape {

//! Rows grouped by colour, in increasing row order within each colour (deterministic).
std::vector<std::vector<int>> color_rows(const RowSparseMatrix& A);

}  // namespace fairshape
