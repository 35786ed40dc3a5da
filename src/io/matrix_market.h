// Matrix Market coordinate format, so assembled systems load in SciPy (scipy.io.mmread) or MATLAB.
#pragma once

#include <string>

#include "fairshape/core/types.h"

namespace fairshape {

//! symmetric = true writes only the lower triangle with the `symmetric` qualifier.
void write_matrix_market(const SparseMatrix& A, const std::string& path, bool symmetric = false);
//! A dense matrix in the `array real general` format (column-major, 17 significant digits).
void write_matrix_market(const Eigen::MatrixXd& M, const std::string& path);
//! Reads `coordinate real|integer general|symmetric`. \throw ParseError naming the line.
SparseMatrix read_matrix_market(const std::string& path);

}  // namespace fairshape
