// Internal: fairshape never writes inf or NaN into a mesh, curve, data array or matrix. A
// result that holds one is refused whole, naming where, before its file is opened (so nothing
// partial is left behind); the caller decides what it means (an overflowing solve, an input
// too large for the computation).
#pragma once

#include <Eigen/Core>
#include <string>

#include "fairshape/core/types.h"

namespace fairshape::io::internal {

//! \throw SolverError "<path>: not written: <row_name> <r> has a non-finite value (…)".
void require_finite(const Eigen::Ref<const Eigen::MatrixXd>& m, const std::string& path, const std::string& row_name);
//! The same for a sparse matrix's stored entries ("entry (i, j) is inf").
void require_finite(const SparseMatrix& A, const std::string& path);

}  // namespace fairshape::io::internal
