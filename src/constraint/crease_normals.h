// Normal constraints at a vertex on a sharp crease. A normal constraint at a vertex makes the
// tangents of the vertex's local quadratic fit (divided differences over its one-ring,
// Boier-Martin et al., "Detail-preserving variational surface design with multiresolution
// constraints", §4.2) perpendicular to the requested normal. Where a sharp crease runs
// through the vertex the surface has a different normal on each side, and a fit across the
// whole ring would average the two sides and bend both. The constraint is refused there with
// a message that names, per side, the surface point `at: {face, uv, level}` at this vertex on
// a face of that side: a normal there is the limit normal of that side (OpenSubdiv Bfr
// evaluates the face's own patch, whose derivatives at a crease are one-sided).
//
// "Sharp" here is what the bending energy treats as sharp (energy/divided_differences.h,
// sector_fits): a tagged edge of sharpness > 0 at the vertex's level, two or more at an
// interior vertex, one or more at a boundary vertex; and an infinitely sharp corner tag (no
// tangent plane at all). A dart, or a semi-sharp corner tag alone, leaves the ring whole.
#pragma once

#include <string>

#include "fairshape/mesh/surface_mesh.h"
#include "fairshape/subdivision/limit_evaluation.h"
#include "fairshape/subdivision/scheme.h"

namespace fairshape {

//! \throw InvalidInput for a normal constraint at `vertex` of `level` where the ring is split
//! by sharp edges or the vertex is an infinitely sharp corner. `has_finer_level`: whether the
//! hierarchy has level + 1, where a non-quad Catmull-Clark face's corner can be addressed.
void refuse_normal_on_crease(const SurfaceMesh& mesh, const SubdivisionOptions& rules, int level, int vertex,
                             bool has_finer_level, const std::string& label);

//! \throw InvalidInput for a normal at the surface point `at` that a closest-point search
//! (`nearest_on_limit`) found on a sharp crease: on a side of its face that is a tagged sharp
//! edge, or at a face corner refuse_normal_on_crease refuses. Which side's normal the point
//! carries would then be the search's accident; the message names the sides' faces.
void refuse_normal_on_crease_point(const SurfaceMesh& mesh, const SubdivisionOptions& rules, int level,
                                   const FaceParameter& at, bool has_finer_level, const std::string& label);

}  // namespace fairshape
