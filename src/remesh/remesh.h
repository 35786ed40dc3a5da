// Semi-regular remeshing of a dense triangle mesh into a multiresolution subdivision surface.
//  1. Base: about K triangles by CGAL edge collapse or CGAL isotropic remeshing (for Catmull-
//     Clark with a quad-dominant base: about 2K, then pairs of them merged into quads,
//     quad_pairing.h). Neither wins everywhere: measured at 600 faces and 4 levels, the
//     collapse base keeps the tips of the cow's horns and tail that an isotropic base rounds
//     off (Hausdorff 0.4 % against 1.9 %), which no finer level recovers; the isotropic base has
//     even edges and follows fandisk's flat faces (edge ratio 13 against 14,000). By default
//     both are made and the result nearer the targets is kept.
//  2. Coarse to fine, level by level: subdivide, move each new vertex along its normal onto the
//     dense surface (closest_point.h, facing_points), then even out the spacing by tangential
//     relaxation and re-projection, and pin the vertex nearest to any dense vertex the level
//     misses by more than an edge onto it. Each level starts from the previous, fitted one, so
//     a vertex only moves a fraction of an edge: projecting only the finest level of the smooth
//     base instead bunches vertices into concave parts and jumps across thin ones. Every one of
//     these moves is guarded (relaxation.h, keep_even_moves): a vertex whose edges it would take
//     further from the level's mean edge than they were, and than a band, stays where it was.
//     Unguarded, projection dropped several vertices onto one claw tip (zero-length edges),
//     relaxation drifted rings along tapering tubes and pins stretched their neighbourhoods,
//     and the finest level's longest/shortest edge ratio reached 114-313 on homer and the
//     mannequin (papers/boier-martin/README.md, "Remesher quality").
//  3. Analysis (MultiresSurface::analyze) into base + details: synthesis gives back step 2's
//     finest level.
// The report measures the result against the dense surface (quality.h).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "fairshape/subdivision/multires_surface.h"

namespace fairshape {

enum class RemeshBase {
  QuadDominant,  // Catmull-Clark only: triangles paired into quads (Loop always uses triangles)
  Triangles,
};

// The earlier pipeline's steps stay selectable, so what each step buys can be measured
// (papers/boier-martin/README.md, "Remesher quality").
enum class BaseMethod {
  Auto,          // both below, keeping the result nearer the quality targets (remesh.cpp)
  Isotropic,     // isotropic_base: near-equilateral triangles
  EdgeCollapse,  // simplify_to_faces: quadric-like collapse, anisotropic triangles
};
enum class FitMethod {
  LevelByLevel,  // project and relax every level, coarse to fine
  Finest,        // project only the finest level of the smooth base (plain closest points), relax it
};

struct RemeshOptions {
  SubdivisionOptions subdivision;
  int base_faces = 500;
  int levels = 3;
  Backend backend = kFastestBackend;
  // Tangential relaxation + re-projection rounds per level, before each of the two feature-pin
  // passes and after the last (so 1.5x as many in all). Unguarded, more was not better on thin
  // parts: each round drifted vertices along a tail or a horn (cow, 600 faces, 4 levels: edge
  // ratio 100 at 3-4 rounds, 230-525 at 2, 6, 8 and 12); guarded: 102 / 52 / 50 / 100 / 49 at
  // 2 / 3 / 4 / 6 / 8 (papers/boier-martin/README.md, "Remesher quality").
  int relax_rounds = 4;
  RemeshBase base = RemeshBase::QuadDominant;
  BaseMethod base_method = BaseMethod::Auto;
  FitMethod fit = FitMethod::LevelByLevel;
  // Every move of a vertex (projection, relaxation, pin) is kept only if the worst of its edges
  // stays within [mean/band, band*mean] of the level's mean edge, or is no worse than before
  // (relaxation.h, keep_even_moves). Pins get a wider band: a pin that cannot be placed is
  // dropped, and with it the tip it would have reached (Hausdorff distance); at 2 the
  // isotropic base loses the cow's horns and homer's fingers (5.1 % and 2.5 %), at 4 it keeps
  // them and bounds the ratio the pins cause (papers/boier-martin/README.md, "Remesher quality").
  double even_band = 3.0;
  double pin_band = 4.0;
  // Spacing of the report's Hausdorff samples, relative to the bounding-box diagonal: the
  // sampled distance is within this of the true one (cost grows with its inverse square).
  double sample_spacing = 1e-3;
};

// The quality targets (README.md, remeshing): a remesh that misses one says so (RemeshReport::misses).
inline constexpr double kHausdorffTarget = 0.015;  // of the dense mesh's bounding-box diagonal
inline constexpr double kEdgeRatioTarget = 100;    // longest / shortest finest-level edge

struct RemeshReport {
  int base_faces_requested = 0, base_faces = 0, fine_vertices = 0, fine_faces = 0;
  double bbox_diagonal = 0;   // of the dense mesh
  double hausdorff = 0;       // two-sided, finest level <-> dense, absolute, sampled on both surfaces
  double dense_to_fine = 0, fine_to_dense = 0;  // its two sides
  double sample_spacing = 0;  // of the Hausdorff samples: the true value is within this of `hausdorff`
  double shortest_edge = 0, longest_edge = 0;  // of the finest level
  Vec3 shortest_at = Vec3::Zero(), longest_at = Vec3::Zero();  // their midpoints, to look at
  // Finest vertices left off the dense surface (keep_even_moves held them back where landing
  // would have crowded or stretched their edges), and the farthest one's distance.
  int off_surface = 0;
  double off_surface_max = 0;
  int unprojected = 0;  // finest vertices with no facing dense surface point within reach (left off it)
  std::map<int, int> base_valence, fine_valence;  // valence -> vertex count
  BaseMethod base_method = BaseMethod::EdgeCollapse;  // the base the result was made from
  double seconds = 0;  // remeshing (both bases for Auto, and then their measuring too)
  double edge_ratio() const { return longest_edge / shortest_edge; }
  double hausdorff_relative() const { return hausdorff / bbox_diagonal; }
  //! One line per missed target, saying by how much; empty when both are met.
  std::vector<std::string> misses() const;
};

//! \throw InvalidInput when the input is not a triangle mesh, K is out of range or the base
//! made has a face count far from K, or the projection fails (non-finite points).
MultiresSurface remesh(const SurfaceMesh& dense, const RemeshOptions& opt, RemeshReport* report);

}  // namespace fairshape
