// Semi-regular remeshing of a dense triangle mesh into a multiresolution subdivision surface:
// simplify to about K faces (CGAL edge collapse, manifold by construction), subdivide L levels, move the finest vertices to
// their closest points on the dense surface (CGAL AABB tree), even out their spacing by
// tangential relaxation and re-projection, then analyse into base + details.
#pragma once

#include "subdivision/multires_surface.h"

namespace fairshape {

struct RemeshOptions {
  SubdivisionOptions subdivision;
  int base_faces = 500;
  int levels = 3;
  Backend backend = Backend::Optimized;
  int relax_rounds = 40;  // tangential relaxation + re-projection rounds after projecting
};

struct RemeshReport {
  int base_faces = 0, fine_vertices = 0;
  double bbox_diagonal = 0;
  double hausdorff = 0;        // two-sided, fine <-> dense, absolute
  double rms_fine_to_dense = 0;
  double shortest_edge = 0;  // of the finest level: projection without relaxation collapses edges
};

//! \throw InvalidInput when the input is not a triangle mesh, K is out of range, or the
//! projection fails (non-finite points).
MultiresSurface remesh(const SurfaceMesh& dense, const RemeshOptions& opt, RemeshReport* report);

}  // namespace fairshape
