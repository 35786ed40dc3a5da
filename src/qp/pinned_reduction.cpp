#include "fairshape/qp/pinned_reduction.h"

#include "fairshape/problem/constrained_system.h"

namespace fairshape::qp {

namespace {

// The columns `cols` of the rows `rows` of M (indices into M), as a |rows| × |cols| matrix.
SparseMatrix submatrix(const SparseMatrix& M, const std::vector<int>& rows, const std::vector<int>& cols) {
  std::vector<int> row_at(static_cast<std::size_t>(M.rows()), -1), col_at(static_cast<std::size_t>(M.cols()), -1);
  for (std::size_t i = 0; i < rows.size(); ++i) row_at[static_cast<std::size_t>(rows[i])] = static_cast<int>(i);
  for (std::size_t j = 0; j < cols.size(); ++j) col_at[static_cast<std::size_t>(cols[j])] = static_cast<int>(j);
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < M.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(M, k); it; ++it) {
      const int r = row_at[static_cast<std::size_t>(it.row())], c = col_at[static_cast<std::size_t>(it.col())];
      if (r >= 0 && c >= 0) t.emplace_back(r, c, it.value());
    }
  SparseMatrix out(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols.size()));
  out.setFromTriplets(t.begin(), t.end());
  out.makeCompressed();
  return out;
}

}  // namespace

PinnedReduction::PinnedReduction(const SparseMatrix& H, const SparseMatrix& A) {
  const Eigen::Index n = H.rows();
  // Each row's entries (A is column-major: one pass over its non-zeros).
  std::vector<int> count(static_cast<std::size_t>(A.rows()), 0), only(static_cast<std::size_t>(A.rows()), -1);
  std::vector<double> value(static_cast<std::size_t>(A.rows()), 0.0);
  for (int k = 0; k < A.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(A, k); it; ++it)
      if (it.value() != 0) {
        const auto r = static_cast<std::size_t>(it.row());
        ++count[r];
        only[r] = static_cast<int>(it.col());
        value[r] = it.value();
      }
  std::vector<char> is_pinned(static_cast<std::size_t>(n), 0);
  for (int r = 0; r < A.rows(); ++r) {
    const auto i = static_cast<std::size_t>(r);
    if (count[i] != 1 || is_pinned[static_cast<std::size_t>(only[i])]) continue;
    is_pinned[static_cast<std::size_t>(only[i])] = 1;
    pinned_.push_back({only[i], r, value[i]});
  }
  std::vector<int> pinned_unknowns;
  for (const Pin& p : pinned_) pinned_unknowns.push_back(p.unknown);
  // H_FF, H_FP and the free unknowns as the paper split's elimination of held vertices forms them.
  energy_ = reduce(H, Eigen::MatrixXd::Zero(n, 1), pinned_unknowns, Eigen::MatrixXd::Zero(n_pinned(), 1));
  // The rows left: those that reach a free unknown (a row among pinned unknowns only is met or
  // not by the pins alone, which the caller's check of every original row sees).
  std::vector<char> reaches_free(static_cast<std::size_t>(A.rows()), 0);
  for (int k = 0; k < A.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(A, k); it; ++it)
      if (it.value() != 0 && !is_pinned[static_cast<std::size_t>(it.col())]) reaches_free[static_cast<std::size_t>(it.row())] = 1;
  for (int r = 0; r < A.rows(); ++r)
    if (reaches_free[static_cast<std::size_t>(r)]) rows_.push_back(r);
  A_F_ = submatrix(A, rows_, energy_.free);
  A_P_ = submatrix(A, rows_, pinned_unknowns);
}

Eigen::MatrixXd PinnedReduction::pinned_values(const Eigen::MatrixXd& b) const {
  Eigen::MatrixXd v(static_cast<Eigen::Index>(pinned_.size()), b.cols());
  for (std::size_t i = 0; i < pinned_.size(); ++i) v.row(static_cast<Eigen::Index>(i)) = b.row(pinned_[i].row) / pinned_[i].coefficient;
  return v;
}

Eigen::MatrixXd PinnedReduction::reduced_f(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b) const {
  return energy_.restrict_to_free(f) - energy_.coupling * pinned_values(b);
}

Eigen::MatrixXd PinnedReduction::reduced_b(const Eigen::MatrixXd& b) const {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(rows_.size()), b.cols());
  for (std::size_t r = 0; r < rows_.size(); ++r) out.row(static_cast<Eigen::Index>(r)) = b.row(rows_[r]);
  return out - A_P_ * pinned_values(b);
}

Eigen::MatrixXd PinnedReduction::expand(const Eigen::MatrixXd& p_free, const Eigen::MatrixXd& b) const {
  return energy_.expand(p_free, pinned_values(b));
}

}  // namespace fairshape::qp
