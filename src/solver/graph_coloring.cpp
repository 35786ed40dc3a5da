#include "fairshape/solver/graph_coloring.h"

namespace fairshape {

std::vector<std::vector<int>> color_rows(const RowSparseMatrix& A) {
  const int n = static_cast<int>(A.rows());
  std::vector<int> color(n, -1);
  std::vector<int> seen_at;  // seen_at[c] == i: colour c is taken by a neighbour of row i
  std::vector<std::vector<int>> classes;
  for (int i = 0; i < n; ++i) {
    for (RowSparseMatrix::InnerIterator it(A, i); it; ++it) {
      const int c = it.col() != i ? color[it.col()] : -1;
      if (c >= 0) seen_at[c] = i;
    }
    int c = 0;
    while (c < static_cast<int>(seen_at.size()) && seen_at[c] == i) ++c;
    if (c == static_cast<int>(seen_at.size())) {
      seen_at.push_back(-1);
      classes.emplace_back();
    }
    color[i] = c;
    classes[c].push_back(i);
  }
  return classes;
}

}  // namespace fairshape
