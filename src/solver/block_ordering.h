// A renumbering of a sparse symmetric system for block multicolour Gauss-Seidel: rows grouped
// into compact blocks (grown breadth-first over the matrix graph), the block graph coloured,
// and the rows renumbered so that each colour's blocks — and each block's rows — are
// contiguous. A colour's sweep then streams one contiguous stretch of the matrix, and a row's
// neighbours are mostly in its own block, i.e. in cache; point multicolouring scatters every
// colour over the whole matrix instead.
#pragma once

#include <utility>
#include <vector>

#include "fairshape/core/types.h"
#include "fairshape/solver/symmetric_rows.h"

namespace fairshape {

struct BlockOrdering {
  std::vector<int> new_of_old, old_of_new;
  //! Row ranges [begin, end) of the blocks, in the new numbering, per colour.
  std::vector<std::vector<std::pair<int, int>>> color_blocks;

  //! Blocks of about `block_size` rows. \throw InvalidInput for a non-square matrix.
  static BlockOrdering build(const RowSparseRef& A, int block_size);
  //! The block size for `rows` rows: `max_block_size`, or less on small systems so that each
  //! of a handful of colours still has blocks for every thread (at least 64 blocks).
  static int block_size_for(Eigen::Index rows, int max_block_size);
  bool empty() const { return new_of_old.empty(); }
  int colors() const { return static_cast<int>(color_blocks.size()); }
  //! Q A Qᵀ (rows and columns renumbered).
  RowSparseMatrix permute(const RowSparseRef& A) const;
};

//! Q_fine P Q_coarseᵀ for a prolongation between two renumbered levels (an empty ordering is
//! the identity).
SparseMatrix permute_prolongation(const SparseMatrix& P, const BlockOrdering& fine, const BlockOrdering& coarse);

}  // namespace fairshape
