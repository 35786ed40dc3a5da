#include "fairshape/design/constrained_freedom.h"

#include <Eigen/SVD>

#include <set>
#include <unordered_map>

namespace fairshape {

ConstrainedFreedom constrained_freedom(const SparseMatrix& A, int max_columns) {
  ConstrainedFreedom out;
  const SparseMatrix rows = A.transpose();  // column r: row r of A
  std::set<int> pinned, reached;
  for (int r = 0; r < rows.outerSize(); ++r) {
    int entries = 0, last = -1;
    for (SparseMatrix::InnerIterator it(rows, r); it; ++it)
      if (it.value() != 0) ++entries, last = static_cast<int>(it.row()), reached.insert(last);
    if (entries == 1) pinned.insert(last);
  }
  for (int c : reached)
    if (!pinned.count(c)) out.columns.push_back(c);
  if (out.columns.empty() || static_cast<int>(out.columns.size()) > max_columns) {
    out.columns.clear();
    return out;
  }
  std::unordered_map<int, int> local;
  for (std::size_t k = 0; k < out.columns.size(); ++k) local[out.columns[k]] = static_cast<int>(k);
  // The rows that reach a free column, restricted to the free columns (the pinned ones are fixed).
  std::vector<Eigen::RowVectorXd> kept;
  for (int r = 0; r < rows.outerSize(); ++r) {
    Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(static_cast<Eigen::Index>(out.columns.size()));
    bool any = false;
    for (SparseMatrix::InnerIterator it(rows, r); it; ++it) {
      const auto f = local.find(static_cast<int>(it.row()));
      if (f == local.end()) continue;
      row[f->second] = it.value();
      any = true;
    }
    if (any) kept.push_back(row);
  }
  Eigen::MatrixXd M(static_cast<Eigen::Index>(kept.size()), static_cast<Eigen::Index>(out.columns.size()));
  for (std::size_t r = 0; r < kept.size(); ++r) M.row(static_cast<Eigen::Index>(r)) = kept[r];
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(M, Eigen::ComputeFullV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  const double cut = 1e-10 * (sigma.size() ? sigma[0] : 0.0);
  Eigen::Index rank = 0;
  while (rank < sigma.size() && sigma[rank] > cut) ++rank;
  out.basis = svd.matrixV().rightCols(M.cols() - rank);
  return out;
}

}  // namespace fairshape
