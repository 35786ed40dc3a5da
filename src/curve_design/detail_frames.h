// Details in local frames (`details: local_frames`), as in Finkelstein and
// Salesin's "Multiresolution curves", on which Sauvage, Hahmann and Bonneau's "Length
// preserving multiresolution editing of curves" builds. The paper's lazy-wavelet details
// d^j_i are vectors in world coordinates: when an edit turns a coarse segment, its details do
// not turn with it and the reconstructed attracting curve C_A misses the lengths at the fine
// levels (23.6 % at w = 1 in Figure 4's first loop). Here a detail is stored in the frame
// (t, n, b) of its level-j segment [c_i, c_i+1] and rebuilt in that segment's frame after the
// edit.
//
// The frame. t is the segment's direction. For the coordinates of a polygon's details
// (`segment_frames`) n and b come from parallel transport along the polygon (the rotation-
// minimizing frame of a polyline: each frame is the previous one turned by the least rotation
// taking one segment direction to the next), started from the first bend (the part of the
// first non-parallel segment direction normal to t_0), so the coordinates are invariant under
// rigid motions; in the plane n is the in-plane normal, b = ±z. A straight polygon has no
// bend: its first normal is taken from the world axis least aligned with t_0, so the
// coordinates of a straight polygon's details are not rigid-invariant (nothing in it fixes a
// turn about its line; reconstruction is exact all the same).
// For an edit the frame of segment i is the reference frame turned by the least rotation that
// takes the reference direction to the edited one (`turn_details`), not the edited polygon's
// own transported frame: in 3-D a transported frame picks up a twist (holonomy) across an
// edited stretch and would turn every detail downstream of it, which breaks the locality of
// the edit. Both agree in the plane (there the least rotation is the rotation about z, i.e.
// Finkelstein and Salesin's tangent/normal frame), and wherever a segment is not edited the
// detail is kept bit for bit.
#pragma once

#include <vector>

#include "fairshape/core/types.h"

namespace fairshape {

//! One frame per segment of a polygon (columns t, n, b; closed polygons include the closing
//! segment), by parallel transport as above.
std::vector<Eigen::Matrix3d> segment_frames(const MatrixX3& polygon, bool closed);

//! Details (one row per segment) into / out of their segments' frames.
MatrixX3 details_to_frames(const MatrixX3& detail, const std::vector<Eigen::Matrix3d>& frames);
MatrixX3 details_from_frames(const MatrixX3& local, const std::vector<Eigen::Matrix3d>& frames);

//! The details of `reference` (a level-j polygon) carried onto `edited` (the same polygon after
//! an edit): each row turned by the least rotation taking its reference segment direction to
//! the edited one; rows of unchanged segments are returned unchanged.
MatrixX3 turn_details(const MatrixX3& detail, const MatrixX3& reference, const MatrixX3& edited, bool closed);

}  // namespace fairshape
