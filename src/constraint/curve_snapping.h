// Curves on a surface turned into vertex chains — our take on the re-parameterization that
// Boier-Martin et al.'s Appendix borrows from Biermann et al. ("Sharp features on
// multiresolution subdivision surfaces"): vertices close enough to the curve are snapped onto
// it, and where the chain of snapped vertices has a gap the next finer level is tried (the
// refinement step), until the approximation property holds:
//   (AP) consecutive chain vertices share a face (they are joined by an edge or a face
//        diagonal), the chain runs along the curve in order, and its ends reach the curve's.
// We do not move the rest vertices in the parameter domain (that would re-sample the
// surface and its details); a snapped vertex is instead constrained to the target curve at
// its parameter, so the deformation carries out the snap (papers/boier-martin/README.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "fairshape/mesh/surface_mesh.h"

namespace fairshape {

//! A polyline lying on a surface, finely sampled; `source` is each sample's position along
//! the designer's control polygon (segment index + fraction), so targets can be interpolated.
struct CurveOnSurface {
  MatrixX3 points;
  std::vector<double> arc;     // arc length at each sample
  std::vector<double> source;  // control-polygon parameter at each sample
  bool closed = false;
};

struct SnappedChain {
  std::vector<int> vertices;   // in curve order
  std::vector<Vec3> on_curve;  // the curve point each vertex snapped to
  std::vector<double> source;  // its control-polygon parameter
};

//! Samples the control polygon at steps of at most `step`, projects the samples onto `mesh`
//! (closest point). \throw InvalidInput naming the place where a sample lies farther than
//! `max_distance` from the surface (the curve leaves the surface).
CurveOnSurface project_curve(const SurfaceMesh& mesh, const MatrixX3& control, bool closed, double step,
                             double max_distance, const std::string& who);

//! Snaps the vertices of `mesh` lying within `snap_ratio` × their shortest edge of the curve.
//! std::nullopt when (AP) fails, with the reason in `why`.
std::optional<SnappedChain> snap_vertices(const SurfaceMesh& mesh, const CurveOnSurface& curve, double snap_ratio,
                                          std::string* why);

}  // namespace fairshape
