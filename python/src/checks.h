// The checks every binding makes at the door, so Python never sees a crash or a silent NaN:
// indices against their range (InvalidIndex, an IndexError), float arguments finite
// (InvalidInput, a ValueError), and every array, mesh or hierarchy handed back finite (one
// helper, one message).
#pragma once

#include <string>

#include "fairshape/core/error.h"
#include "fairshape/core/types.h"
#include "fairshape/mesh/surface_mesh.h"
#include "fairshape/subdivision/multires_surface.h"

namespace fairshape::python {

//! An index out of its range: fairshape.InvalidIndex in Python, both an InvalidInput and an
//! IndexError.
class InvalidIndex : public InvalidInput {
  using InvalidInput::InvalidInput;
};

//! `i` as an index into `n` items. \throw InvalidIndex "WHO: NAME = i is out of range (valid:
//! 0..n-1, the n ITEMS)" — the C++ side would read out of bounds or abort.
int index_arg(long long i, long long n, const std::string& who, const std::string& name, const std::string& items);

//! \throw InvalidInput naming `name` when `v` is NaN or infinite.
double finite_arg(double v, const std::string& name);
//! \throw InvalidInput naming `name` and the first non-finite entry.
void finite_arg(const Eigen::Ref<const Eigen::MatrixXd>& m, const std::string& name);
void finite_arg(const SparseMatrix& m, const std::string& name);

//! The result checks: \throw Error "WHAT: the result is not finite (entry ...)" rather than
//! hand NaN or infinity to Python as an answer.
void finite_result(const Eigen::Ref<const Eigen::MatrixXd>& m, const std::string& what);
void finite_result(const SparseMatrix& m, const std::string& what);
void finite_result(const RowSparseMatrix& m, const std::string& what);
void finite_result(const SurfaceMesh& mesh, const std::string& what);
void finite_result(const MultiresSurface& h, const std::string& what);

//! The helpers above, returning their argument, for `return checked(X, "...")`.
template <class T>
T checked(T value, const std::string& what) {
  finite_result(value, what);
  return value;
}

}  // namespace fairshape::python
