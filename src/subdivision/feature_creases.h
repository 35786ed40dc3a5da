// Feature-angle crease detection: the config way to mark creases on a mesh without tags
// (`input.crease_angle` of surface-edit runs). An edge whose dihedral angle (between the
// normals of its two faces; 0 when flat) exceeds the threshold becomes infinitely sharp.
// A vertex where such feature lines end (one sharp edge) or meet (three or more) becomes an
// infinitely sharp corner: the three-or-more case is OpenSubdiv's classification anyway; a
// line's end is pinned too, so that a feature line ends at a point instead of fading out as
// OpenSubdiv's dart rule would make it.
#pragma once

#include "fairshape/mesh/surface_mesh.h"

namespace fairshape {

struct DetectedCreases {
  int edges = 0, corners = 0;
};

//! Marks the edges sharper than `degrees` (in (0, 180)) and their corner vertices on `mesh`,
//! keeping sharpness it has already (tags). \throw InvalidInput for a threshold out of range.
DetectedCreases mark_feature_creases(SurfaceMesh& mesh, double degrees);

//! The dihedral angle of interior edge e in degrees (0: flat); 0 on a boundary edge.
double dihedral_angle_degrees(const SurfaceMesh& mesh, int e);

}  // namespace fairshape
