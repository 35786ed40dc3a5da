// The explicit length step of Sauvage, Hahmann and Bonneau, "Length preserving multiresolution
// editing of curves" (§4.1), kept inside the edit's support (edit_support.h).
//
// The paper lets "some control points at level w" move when the edit stretches the curve and
// leaves how to its reference [16]. Moving them in a sweep from the dragged point (the `sweep`
// way, explicit_length.h) drags the rest of the curve like a rope. Here the level-e control
// points stay where the edit put them (moved or not) and only the level-w points strictly
// between them, in level-e segments next to a moved point, may move. Each such level-e segment
// is a chain of 2^(w−e) level-w segments with fixed ends; a level-w segment k can be given its
// two level-(w+1) lengths only if |P_k P_k+1| ≤ r_k = a_k + b_k. When some segment of a chain
// is longer, the chain's free points are blended towards the straight chain S (its chord cut in
// proportion to the r_k, on which every segment is r_k·|chord| / Σr ≤ r_k) by the least
// t ∈ (0, 1] that makes every segment short enough — a closed-form root per segment, since
// |(1−t)d + t·e| is convex in t. The excess is thereby spread over the chain's segments and
// nothing outside the support moves. A chain whose chord exceeds Σr cannot reach with the
// control points where the edit put them (the edit asks for more length than the curve has
// there, e.g. a drag beyond the curve's length): the moved control points are first pulled
// back along their chords just enough (alternating projections over the chains; the report's
// worst_pull_back, said in runs.csv) — the alternative, moving unedited points, is what made
// the sweep global. A chain still too long after that (not reached from a valid reference) is
// left straight, every segment equally too long, and counted in unreachable_chains.
// Midpoints are then placed (place_midpoint) on the support's level-w segments only, so
// every detail outside keeps its value bit for bit.
#pragma once

#include <vector>

#include "fairshape/core/backend.h"
#include "fairshape/curve_design/explicit_length.h"

namespace fairshape {

//! \param coarse level-w points (after the edit); free points inside the support may move.
//! \param detail d^w; rows of the support's segments replaced.
//! \param target the reference lengths of the level-(w+1) edges (2 per level-w segment).
//! \param moved_e level-e indices of the moved control points; \param stride 2^(w−e).
ExplicitLengthReport preserve_lengths_locally(MatrixX3& coarse, MatrixX3& detail, const Eigen::VectorXd& target,
                                              bool closed, const std::vector<int>& moved_e, int stride);

}  // namespace fairshape
