// The explicit length-preserving step of Sauvage, Hahmann and Bonneau, "Length preserving
// multiresolution editing of curves" (§4.1): at level w, replace the details d^w so that every
// edge of the level-(w+1) polygon gets the reference length again, which turns excess length
// into one wrinkle per level-w segment.
//
// Choices the paper leaves open (its reference [16] is an unpublished thesis):
//  * the new midpoint m of segment [P, Q] lies on the circle (a sphere intersection in 3D)
//    of points a from P and b from Q (a, b: the reference lengths of its two children); we take
//    the point of that circle nearest to the current midpoint, so untouched parts of the curve
//    keep their details exactly and wrinkles bulge on the side the old detail was on. A
//    midpoint exactly on PQ (a straight reference) bulges to the left of PQ in the xy plane.
//  * when |PQ| > a + b (stretching) no midpoint reaches. Two ways (`explicit_step`):
//    `local` (explicit_local.h, the default): only the level-w points inside the edit's
//    support move, each chain between fixed control points straightened just enough;
//    `sweep` (here, the first implementation): level-w points are pulled in along
//    the polygon, follow-the-leader, outwards from the anchor (the first moved control point),
//    so what the user dragged stays where it was put and the far parts follow like a rope.
//    On a closed curve the two sweeps meet opposite the anchor; the segment where they meet
//    is left to the optimization.
//  * |PQ| < |a − b| (no intersection: one child far longer than the other and the chord, a
//    spike): no midpoint gives both lengths, and the paper's step only replaces details, so
//    the midpoint goes on the line PQ at distance a from P (the longer child beyond the
//    shorter) and the level-(w+1) lengths stay wrong there. Such midpoints are counted
//    (ExplicitLengthReport::unplaceable_midpoints) and the lengths the step left are measured
//    (length_error): the editing loop reports them and a run fails on them unless allowed
//    (papers/sauvage/README.md, "Explicit step on spiky detail").
#pragma once

#include "fairshape/core/backend.h"
#include "fairshape/core/types.h"

namespace fairshape {

struct ExplicitLengthReport {
  int shortened_segments = 0;  // level-w segments pulled in (stretching)
  int moved_midpoints = 0;     // level-(w+1) midpoints that had to move
  // `local` only: chains of the support whose fixed ends are farther apart than the chain's
  // reference length (no placement inside the support keeps the lengths), and the worst
  // relative excess chord / length − 1 among them; those chains are left straight.
  int unreachable_chains = 0;
  double worst_excess = 0;
  // `local` only: how far moved control points had to be pulled back towards their fixed
  // neighbours because the edit asked for more length than the curve has there (0: none).
  double worst_pull_back = 0;
  // Level-w segments whose chord is shorter than |a − b| (no midpoint keeps both children), and
  // the largest relative error of the level-(w+1) lengths after the step, measured on the
  // polygon it produced (both ways; set by the editing loop).
  int unplaceable_midpoints = 0;
  double length_error = 0;
};

//! Level-w segments of `coarse` whose chord is shorter than |a − b| (a, b its children's targets).
int count_unplaceable_midpoints(const MatrixX3& coarse, const Eigen::VectorXd& target, bool closed);

//! \param coarse level-w points; moved in the stretching case.
//! \param detail d^w, replaced.
//! \param target the reference lengths of the level-(w+1) edges (2 per level-w segment).
//! \param anchor level-w index kept in place when segments are pulled in.
ExplicitLengthReport preserve_lengths_explicitly(MatrixX3& coarse, MatrixX3& detail, const Eigen::VectorXd& target,
                                                 bool closed, int anchor, Backend backend);

//! Level-w segment i's new midpoint (the circle point nearest the current one), written into
//! detail row i; returns whether it moved. Shared by both ways.
bool place_midpoint(const MatrixX3& coarse, MatrixX3& detail, const Eigen::VectorXd& target, int i);

}  // namespace fairshape
