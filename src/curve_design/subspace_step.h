// A trust-region step in a small subspace, for curves with many negative-curvature modes (issue
// 25: Figure 1's edit at 131,073 points starts with ~27,000 negative eigenvalues of the reduced
// Hessian; stepping along one eigenvector per iteration leaves one mode at a time).
//  1. Block inverse iteration (subspace iteration, Golub & Van Loan, "Matrix computations",
//     §8.2.4) with the shifted KKT factor: each column one solve [W + σI, Jᵀ; J, 0][w; ·] = [v; 0],
//     so the block stays in the tangent space null(J) and converges to the eigenvectors of the k
//     smallest eigenvalues of the reduced Hessian Zᵀ W Z (σ ≥ −λ_min makes the shifted matrix
//     positive definite there). The block is kept between iterations (a warm start: the curve
//     moves little, so do its soft modes).
//  2. Rayleigh–Ritz on span{s_N, block}: s_N the shifted Newton step, so the subspace step is
//     never worse in the model than the single-vector step it replaces.
//  3. The trust-region subproblem min gᵀs + ½ sᵀ W s, |s| ≤ Δ restricted to that span, solved
//     exactly (Moré and Sorensen, "Computing a trust region step", 1983: the secular equation on
//     the small projected matrix's eigenbasis, with the hard case): several negative modes are
//     left in one step, each by the amount the model asks, instead of one eigenvector filling the
//     rest of the radius.
#pragma once

#include "fairshape/core/types.h"
#include "fairshape/curve_design/kkt_factor.h"

namespace fairshape {

struct SmallTrustRegionStep {
  Eigen::VectorXd c;          // the minimizer's coordinates
  double model = 0;           // gᵀc + ½ cᵀHc at it (≤ 0)
  bool on_boundary = false;   // |c| = Δ
  bool negative_curvature = false;  // H had a negative eigenvalue (the step used it)
};

//! min gᵀc + ½ cᵀHc subject to |c| ≤ radius for a small dense symmetric H (Moré–Sorensen on
//! H's eigendecomposition). In the hard case (g orthogonal to the eigenvector u₁ of a negative
//! smallest eigenvalue) u₁ fills the radius on the side of the largest entry of basis·u₁ (u₁
//! itself without a basis), so the choice is deterministic (both back ends take the same side).
SmallTrustRegionStep solve_small_trust_region(const Eigen::MatrixXd& H, const Eigen::VectorXd& g, double radius,
                                              const Eigen::MatrixXd* basis = nullptr);

struct RitzPairs {
  Eigen::VectorXd values;  // ascending
  Eigen::MatrixXd vectors; // n × k, orthonormal columns, tangent
  int solves = 0;          // back-substitutions spent
};

//! `steps` steps of block inverse iteration on `block` (n × k; replaced by the new block) with a
//! KKT factor already made at W + σI, then Rayleigh–Ritz with W. Columns that lose rank are
//! dropped (the block may come back narrower).
RitzPairs block_inverse_iteration(KktFactor& shifted, const SparseMatrix& W, Eigen::MatrixXd& block, int n_constraints,
                                  int steps);

//! A deterministic start block: columns of smooth and rough oscillations in every coordinate
//! (no random numbers: both back ends and every run start from the same block).
Eigen::MatrixXd initial_block(int n, int k);

struct SubspaceStep {
  Eigen::VectorXd s;        // the step in the full space
  double predicted = 0;     // −(gᵀs + ½ sᵀWs)
  bool negative_curvature = false;
  bool on_boundary = false;
};

//! The exact trust-region step in span{columns of basis} (orthonormalized here; dependent
//! columns dropped) for the model gᵀs + ½ sᵀ W s.
SubspaceStep subspace_trust_region_step(const Eigen::MatrixXd& basis, const SparseMatrix& W, const Eigen::VectorXd& g,
                                        double radius);

}  // namespace fairshape
