#include "checks.h"

#include <cmath>
#include <sstream>

#include "fairshape/core/error.h"

namespace fairshape::python {
namespace {

// "(row r, column c) = nan" of the first entry that is not finite, or empty.
template <class Dense>
std::string first_bad(const Dense& m) {
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c)
      if (!std::isfinite(m(r, c))) {
        std::ostringstream s;
        s << "entry (" << r << ", " << c << ") is " << m(r, c);
        return s.str();
      }
  return "";
}

template <class Sparse>
std::string first_bad_sparse(const Sparse& m) {
  for (Eigen::Index k = 0; k < m.outerSize(); ++k)
    for (typename Sparse::InnerIterator it(m, k); it; ++it)
      if (!std::isfinite(it.value())) {
        std::ostringstream s;
        s << "entry (" << it.row() << ", " << it.col() << ") is " << it.value();
        return s.str();
      }
  return "";
}

[[noreturn]] void not_finite_result(const std::string& what, const std::string& where) {
  throw Error(what + ": the result is not finite (" + where + "); nothing is returned rather than NaN or infinity");
}

}  // namespace

int index_arg(long long i, long long n, const std::string& who, const std::string& name, const std::string& items) {
  if (i < 0 || i >= n)
    throw InvalidIndex(who + ": " + name + " = " + std::to_string(i) + " is out of range (valid: " +
                          (n > 0 ? "0.." + std::to_string(n - 1) : std::string("none")) + ", the " +
                          std::to_string(n) + " " + items + ")");
  return static_cast<int>(i);
}

double finite_arg(double v, const std::string& name) {
  if (!std::isfinite(v)) {
    std::ostringstream s;
    s << name << " = " << v << ": must be a finite number";
    throw InvalidInput(s.str());
  }
  return v;
}

void finite_arg(const Eigen::Ref<const Eigen::MatrixXd>& m, const std::string& name) {
  if (const std::string bad = first_bad(m); !bad.empty()) throw InvalidInput(name + ": every entry must be finite; " + bad);
}

void finite_arg(const SparseMatrix& m, const std::string& name) {
  if (const std::string bad = first_bad_sparse(m); !bad.empty())
    throw InvalidInput(name + ": every entry must be finite; " + bad);
}

void finite_result(const Eigen::Ref<const Eigen::MatrixXd>& m, const std::string& what) {
  if (const std::string bad = first_bad(m); !bad.empty()) not_finite_result(what, bad);
}

void finite_result(const SparseMatrix& m, const std::string& what) {
  if (const std::string bad = first_bad_sparse(m); !bad.empty()) not_finite_result(what, bad);
}

void finite_result(const RowSparseMatrix& m, const std::string& what) {
  if (const std::string bad = first_bad_sparse(m); !bad.empty()) not_finite_result(what, bad);
}

void finite_result(const SurfaceMesh& mesh, const std::string& what) {
  if (const std::string bad = first_bad(mesh.positions()); !bad.empty()) not_finite_result(what + " (positions)", bad);
}

void finite_result(const MultiresSurface& h, const std::string& what) {
  for (int l = 0; l <= h.levels(); ++l)
    finite_result(h.mesh(l), what + ", level " + std::to_string(l));
}

}  // namespace fairshape::python
