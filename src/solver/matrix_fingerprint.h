// What a solver remembers of the matrix it analyzed, so that solve(A, …) can tell whether A is
// that matrix (the contract in solver/solver.h): sizes, stored entries, one hash over the
// sparsity pattern and one over the values. Compared by value, never by address: callers refill
// buffers in place. Taking one is a single pass over A (parallel over column blocks when A is
// large, the same hash for any thread count), about the cost of one matrix-vector product:
// cheap next to the factorization or colouring it guards. Two different matrices share a hash
// with probability about 2⁻⁶⁴; nothing here builds matrices to collide.
#pragma once

#include <cstdint>

#include "fairshape/core/types.h"

namespace fairshape {

class MatrixFingerprint {
 public:
  //! The fingerprint of no matrix: it matches no matrix's.
  MatrixFingerprint() = default;
  explicit MatrixFingerprint(const SparseMatrix& A);

  //! Same sizes and the same stored entries (explicit zeros count), whatever the values.
  bool same_pattern(const MatrixFingerprint& o) const {
    return rows_ >= 0 && rows_ == o.rows_ && cols_ == o.cols_ && nonzeros_ == o.nonzeros_ && pattern_ == o.pattern_;
  }
  //! The same matrix: same pattern and bit-identical values.
  bool operator==(const MatrixFingerprint& o) const { return same_pattern(o) && values_ == o.values_; }
  bool operator!=(const MatrixFingerprint& o) const { return !(*this == o); }

 private:
  Eigen::Index rows_ = -1, cols_ = -1, nonzeros_ = -1;
  std::uint64_t pattern_ = 0, values_ = 0;
};

//! The matrix a solver's analysis is for (none until the first remember()).
class AnalyzedMatrix {
 public:
  void remember(const MatrixFingerprint& f) { fingerprint_ = f; }
  void remember(const SparseMatrix& A) { fingerprint_ = MatrixFingerprint(A); }
  //! After anything else the analysis depends on changed (a multilevel solver's hierarchy).
  void forget() { fingerprint_ = MatrixFingerprint(); }
  const MatrixFingerprint& fingerprint() const { return fingerprint_; }
  //! Whether A is the matrix remembered (sizes, pattern and values).
  bool is(const SparseMatrix& A) const { return fingerprint_ == MatrixFingerprint(A); }

 private:
  MatrixFingerprint fingerprint_;
};

}  // namespace fairshape
