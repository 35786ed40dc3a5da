// Parallel assembly of H = Σ_v G_vᵀ W G_v straight into compressed storage, where each vertex
// v contributes the Gram matrix of a small factor G_v (k rows over the vertex ids of its
// stencil) with diagonal weights W. The triplet route (one triplet per block entry, then a
// serial sort) needs ~1.4 GB and 15 s at a million vertices; here the blocks are never
// formed: every row gathers its entries from the stencils that contain it, in a fixed order,
// so the result is bitwise identical for any thread count.
#pragma once

#include <vector>

#include "fairshape/core/types.h"

namespace fairshape {

//! The factors G_v, flattened: stencil v covers ids[offset[v] .. offset[v+1]) and its factor
//! is the k × size column-major block at factor[k · offset[v]].
struct GramFactors {
  int k = 0;
  std::vector<int> offset{0};
  std::vector<int> ids;
  std::vector<double> factor;
  void append(const std::vector<int>& stencil, const Eigen::MatrixXd& G);  // G: k × |stencil|
  void append(const GramFactors& other);
};

//! Σ_v G_vᵀ diag(weights) G_v as an n × n matrix (TBB-parallel over rows).
SparseMatrix assemble_gram(int n, const GramFactors& f, const Eigen::VectorXd& weights);

}  // namespace fairshape
