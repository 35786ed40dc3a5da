#include "fairshape/io/matrix_market.h"

#include <cstdio>

#include "fairshape/core/atomic_file.h"
#include "fairshape/io/finite_output.h"
#include "fairshape/io/text_scanner.h"

namespace fairshape {

void write_matrix_market(const SparseMatrix& A, const std::string& path, bool symmetric) {
  io::internal::require_finite(A, path);
  long long nnz = 0;
  for (int k = 0; k < A.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(A, k); it; ++it)
      if (!symmetric || it.row() >= it.col()) ++nnz;
  write_atomically(path, [&](std::ostream& os) {
    os << "%%MatrixMarket matrix coordinate real " << (symmetric ? "symmetric" : "general")
       << "\n% written by fairshape\n"
       << A.rows() << ' ' << A.cols() << ' ' << nnz << '\n';
    char buf[64];
    for (int k = 0; k < A.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(A, k); it; ++it) {
        if (symmetric && it.row() < it.col()) continue;
        std::snprintf(buf, sizeof buf, "%.17g", it.value());
        os << it.row() + 1 << ' ' << it.col() + 1 << ' ' << buf << '\n';
      }
  });
}

void write_matrix_market(const Eigen::MatrixXd& M, const std::string& path) {
  io::internal::require_finite(M, path, "row");
  write_atomically(path, [&](std::ostream& os) {
    os << "%%MatrixMarket matrix array real general\n% written by fairshape\n" << M.rows() << ' ' << M.cols() << '\n';
    char buf[64];
    for (Eigen::Index c = 0; c < M.cols(); ++c)
      for (Eigen::Index r = 0; r < M.rows(); ++r) {
        std::snprintf(buf, sizeof buf, "%.17g", M(r, c));
        os << buf << '\n';
      }
  });
}

SparseMatrix read_matrix_market(const std::string& path) {
  const std::string text = io::internal::read_whole_file(path);
  if (text.rfind("%%MatrixMarket", 0) != 0) throw ParseError(path, 1, "missing '%%MatrixMarket' banner");
  const std::string banner = text.substr(0, text.find('\n'));
  if (banner.find("coordinate") == std::string::npos)
    throw ParseError(path, 1, "only the coordinate format is supported");
  const bool symmetric = banner.find("symmetric") != std::string::npos;
  const std::string body = text.substr(text.find('\n') + 1);  // outlives the scanner's view
  io::internal::TextScanner s(body, path, 2);
  while (s.next_line() && s.tokens()[0][0] == '%') {}
  if (s.tokens().size() != 3) s.fail("expected 'rows cols nonzeros'");
  const long long rows = s.to_integer(s.tokens()[0], "rows"), cols = s.to_integer(s.tokens()[1], "cols");
  const long long nnz = s.to_count(s.tokens()[2], "the nonzero count", 6);
  if (rows < 0 || cols < 0 || rows > INT32_MAX || cols > INT32_MAX) s.fail("matrix size out of range");
  Triplets t;
  t.reserve(static_cast<std::size_t>(nnz));
  for (long long k = 0; k < nnz; ++k) {
    if (!s.next_line()) s.fail("file ends after " + std::to_string(k) + " of " + std::to_string(nnz) + " entries");
    if (s.tokens().size() < 3) s.fail("an entry needs 'row col value'");
    const long long i = s.to_integer(s.tokens()[0], "a row index") - 1;
    const long long j = s.to_integer(s.tokens()[1], "a column index") - 1;
    if (i < 0 || i >= rows || j < 0 || j >= cols) s.fail("entry index out of range");
    const double v = s.to_double(s.tokens()[2], "a value");
    t.emplace_back(static_cast<int>(i), static_cast<int>(j), v);
    if (symmetric && i != j) t.emplace_back(static_cast<int>(j), static_cast<int>(i), v);
  }
  SparseMatrix A(rows, cols);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

}  // namespace fairshape
