#include "fairshape/solver/block_ordering.h"

#include <algorithm>

#include "fairshape/core/error.h"
#include "fairshape/solver/graph_coloring.h"

namespace fairshape {
namespace {

// Every row once, breadth-first from row 0 (and from the lowest unvisited row of each further
// connected component).
std::vector<int> breadth_first_order(const RowSparseRef& A) {
  const int n = static_cast<int>(A.rows());
  std::vector<char> visited(static_cast<std::size_t>(n), 0);
  std::vector<int> order;
  order.reserve(static_cast<std::size_t>(n));
  for (int root = 0; root < n; ++root) {
    if (visited[static_cast<std::size_t>(root)]) continue;
    visited[static_cast<std::size_t>(root)] = 1;
    order.push_back(root);
    for (std::size_t head = order.size() - 1; head < order.size(); ++head)
      for (RowSparseRef::InnerIterator it(A, order[head]); it; ++it)
        if (!visited[static_cast<std::size_t>(it.col())]) {
          visited[static_cast<std::size_t>(it.col())] = 1;
          order.push_back(static_cast<int>(it.col()));
        }
  }
  return order;
}

// The pattern of the block graph: block b is coupled to block c when a row of b has an entry in
// a column of c (A symmetric, so the pattern is too).
RowSparseMatrix block_graph(const RowSparseRef& A, const std::vector<int>& block_of,
                            const std::vector<std::vector<int>>& rows_of) {
  const auto blocks = static_cast<Eigen::Index>(rows_of.size());
  std::vector<int> marked_by(rows_of.size(), -1), neighbours;
  RowSparseMatrix B(blocks, blocks);
  for (Eigen::Index b = 0; b < blocks; ++b) {
    neighbours.clear();
    for (int i : rows_of[static_cast<std::size_t>(b)])
      for (RowSparseRef::InnerIterator it(A, i); it; ++it) {
        const int c = block_of[static_cast<std::size_t>(it.col())];
        if (marked_by[static_cast<std::size_t>(c)] == b) continue;
        marked_by[static_cast<std::size_t>(c)] = static_cast<int>(b);
        neighbours.push_back(c);
      }
    std::sort(neighbours.begin(), neighbours.end());
    B.startVec(b);
    for (int c : neighbours) B.insertBack(b, c) = 1.0;
  }
  B.finalize();
  return B;
}

}  // namespace

BlockOrdering BlockOrdering::build(const RowSparseRef& A, int block_size) {
  if (A.rows() != A.cols()) throw InvalidInput("block ordering: the matrix is not square");
  const int n = static_cast<int>(A.rows());
  // Blocks: breadth-first from a seed until the block is full. Seeds are taken in the order of
  // one breadth-first traversal of the whole graph, so consecutive blocks — and consecutive
  // blocks of one colour — are neighbours in space, and a colour's sweep gathers its
  // neighbours' values from a window that moves through memory with it (seeding by the lowest
  // row number instead scattered those gathers over the whole vector: twice the sweep time).
  const std::vector<int> seeds = breadth_first_order(A);
  std::vector<int> block_of(static_cast<std::size_t>(n), -1), bfs_order;
  bfs_order.reserve(static_cast<std::size_t>(n));
  int blocks = 0;
  for (int seed : seeds) {
    if (block_of[static_cast<std::size_t>(seed)] >= 0) continue;
    const std::size_t first = bfs_order.size();
    block_of[static_cast<std::size_t>(seed)] = blocks;
    bfs_order.push_back(seed);
    for (std::size_t head = first; head < bfs_order.size() && bfs_order.size() - first < static_cast<std::size_t>(block_size);
         ++head)
      for (RowSparseRef::InnerIterator it(A, bfs_order[head]); it; ++it) {
        const int j = static_cast<int>(it.col());
        if (block_of[static_cast<std::size_t>(j)] >= 0) continue;
        block_of[static_cast<std::size_t>(j)] = blocks;
        bfs_order.push_back(j);
        if (bfs_order.size() - first == static_cast<std::size_t>(block_size)) break;
      }
    ++blocks;
  }
  // The block graph (blocks coupled by an entry of A), coloured greedily. Built block by block
  // with a marker per neighbour block, not from a triplet per entry of A: at 737k rows such a
  // list is 300 MB (600 MB while it grows), the largest allocation of a level-4 set-up.
  std::vector<std::vector<int>> rows_of(static_cast<std::size_t>(blocks));
  for (int i : bfs_order) rows_of[static_cast<std::size_t>(block_of[static_cast<std::size_t>(i)])].push_back(i);
  const RowSparseMatrix B = block_graph(A, block_of, rows_of);
  const std::vector<std::vector<int>> block_colors = color_rows(B);
  // New numbering: colour by colour, block by block, each block's rows in breadth-first order.
  BlockOrdering o;
  o.old_of_new.reserve(static_cast<std::size_t>(n));
  for (const std::vector<int>& color : block_colors) {
    o.color_blocks.emplace_back();
    for (int blk : color) {
      const int begin = static_cast<int>(o.old_of_new.size());
      for (int i : rows_of[static_cast<std::size_t>(blk)]) o.old_of_new.push_back(i);
      o.color_blocks.back().emplace_back(begin, static_cast<int>(o.old_of_new.size()));
    }
  }
  o.new_of_old.assign(static_cast<std::size_t>(n), -1);
  for (int k = 0; k < n; ++k) o.new_of_old[static_cast<std::size_t>(o.old_of_new[static_cast<std::size_t>(k)])] = k;
  return o;
}

int BlockOrdering::block_size_for(Eigen::Index rows, int max_block_size) {
  constexpr Eigen::Index kMinBlocks = 64, kMinBlockSize = 16;
  return static_cast<int>(std::clamp(rows / kMinBlocks, kMinBlockSize, static_cast<Eigen::Index>(max_block_size)));
}

RowSparseMatrix BlockOrdering::permute(const RowSparseRef& A) const {
  // Row by row into the new order, each row's entries re-sorted by new column: no triplet
  // list (at 1.1M rows one would be 300 MB, more than the matrix).
  FAIRSHAPE_ASSERT(A.isCompressed(), "block ordering: permute needs a compressed matrix");
  const Eigen::Index n = A.rows();
  RowSparseMatrix out(n, A.cols());
  Eigen::VectorXi sizes(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const int old = old_of_new[static_cast<std::size_t>(k)];
    sizes[k] = static_cast<int>(A.outerIndexPtr()[old + 1] - A.outerIndexPtr()[old]);
  }
  out.reserve(sizes);
  std::vector<std::pair<int, double>> row;
  for (Eigen::Index k = 0; k < n; ++k) {
    row.clear();
    for (RowSparseRef::InnerIterator it(A, old_of_new[static_cast<std::size_t>(k)]); it; ++it)
      row.emplace_back(new_of_old[static_cast<std::size_t>(it.col())], it.value());
    std::sort(row.begin(), row.end());
    for (const auto& [col, value] : row) out.insertBackUncompressed(k, col) = value;
  }
  out.makeCompressed();
  return out;
}

SparseMatrix permute_prolongation(const SparseMatrix& P, const BlockOrdering& fine, const BlockOrdering& coarse) {
  std::vector<Eigen::Triplet<double, int>> t;
  t.reserve(static_cast<std::size_t>(P.nonZeros()));
  for (int j = 0; j < P.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(P, j); it; ++it) {
      const int r = fine.empty() ? static_cast<int>(it.row()) : fine.new_of_old[static_cast<std::size_t>(it.row())];
      const int c = coarse.empty() ? j : coarse.new_of_old[static_cast<std::size_t>(j)];
      t.emplace_back(r, c, it.value());
    }
  SparseMatrix out(P.rows(), P.cols());
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

}  // namespace fairshape
