// Region of influence (Boier-Martin et al., "Detail-preserving variational surface design with
// multiresolution constraints", §4.2): a constraint is propagated to a coarse level k of its
// own, and k decides how much of the surface it moves — the whole model when k is coarse
// (Figure 1 b), a local bump when k is fine (Figure 1 c).
//
// The paper leaves the region's extent to its interactive solver (a few Gauss-Seidel sweeps
// spread a change a few rings). An exact solve on the whole of level k spreads it as far as
// the energy reaches, whatever k is (measured: papers/boier-martin/README.md). We make the
// region explicit:
//   region on level k  = the level-k vertices the constraint's propagated rows touch, grown by
//                        `rings` rings of face neighbours; only they move on level k;
//   region on the surface = what those vertices reach on the finest level: the support of
//                        their subdivided basis functions, grown by one ring per finer level
//                        because a detail's local frame follows its one-ring's limit normal.
// Outside it nothing the constraint causes moves, by construction (tested, and re-checked by
// every run: runs.csv's outside_region_move).
#pragma once

#include <vector>

#include "fairshape/core/types.h"
#include "fairshape/mesh/surface_mesh.h"
#include "fairshape/subdivision/multires_surface.h"

namespace fairshape {

struct Influence {
  static constexpr int kEditLevel = -1;   // level: the run's edit level
  static constexpr int kWholeLevel = -1;  // rings: every vertex of the level may move
  //! rings: as many as the edit needs — from kFirstAutoRings, doubled while the pass's result
  //! folds the surface (a region narrower than the handle's move must bend over: measured in
  //! papers/boier-martin/README.md, "Regions that fold").
  static constexpr int kAutoRings = -2;
  static constexpr int kFirstAutoRings = 2;
  int level = kEditLevel;
  int rings = kWholeLevel;
  //! A fixed constraint has nothing to spread: it is held in every pass, with no region.
  bool held = false;
  //! Given a level or rings of its own: solved in its own pass, on its own region.
  bool regional() const { return level != kEditLevel || rings != kWholeLevel; }
  int level_or(int edit_level) const { return level == kEditLevel ? edit_level : level; }
};

//! The vertices within `rings` rings of face neighbours of `seeds` (sorted, unique).
std::vector<int> grow_rings(const SurfaceMesh& mesh, const std::vector<int>& seeds, int rings);

//! 1 for every vertex of level `to` that a change of `moved` (0/1 per vertex of level `from`)
//! can move when the finer levels are re-synthesized with local-frame details: the support of
//! the subdivision operators, grown by one ring per level (the frames' limit normals).
Eigen::VectorXi reached_on_level(const MultiresSurface& h, int from, const Eigen::VectorXi& moved, int to);

}  // namespace fairshape
