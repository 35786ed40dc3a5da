// A x = B solved for the independent columns of B only. A single handle's edit has a
// right-hand side of rank 1 — every column is a multiple of one (B = f dᵀ for the handle's
// offset d; measured: the y column exactly 0 and z = 0.533·x on the cow) — yet a block
// solve pays for every column: an iterative solver's iterations cost about the number of
// columns times one. By linearity, solving the r independent columns and combining their
// solutions gives every column's: X = X_r [I C] (up to the column order), where B = B_r [I C].
// Only columns that ARE dependent (to rounding: 1e-13 of the block's norm) are combined, and
// only from a start of the same dependency (a cold start, or the previous step of a drag along
// one line), so the answer is the block solve's to rounding and the solver's own tolerance.
#pragma once

#include <optional>
#include <vector>

#include "fairshape/solver/solver.h"

namespace fairshape {

//! B's columns as B = B(:, independent) · combination, when some column is dependent.
struct ColumnDependence {
  std::vector<int> independent;     // columns of B solved for
  Eigen::MatrixXd combination;      // #independent × B.cols(): B = B(:, independent) · combination
};

//! The dependence of B's columns to `tolerance` × ‖B‖ (a pivoted QR of B, then the fit checked
//! column by column), or nullopt when every column is needed.
std::optional<ColumnDependence> dependent_columns(const Eigen::MatrixXd& B, double tolerance = 1e-13);

//! solver.solve(A, B, X, cb), but on B's independent columns when that is exact (see above);
//! `cb` still sees the full #rows × B.cols() iterate. The summary gains a note in its message
//! when columns were combined.
SolveSummary solve_independent_columns(Solver& solver, const SparseMatrix& A, const Eigen::MatrixXd& B,
                                       Eigen::MatrixXd& X, const IterationCallback& cb = {});

}  // namespace fairshape
