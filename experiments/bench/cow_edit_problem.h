// The edit every issue-5 benchmark solves: the Figure 2 nose handle on the Catmull-Clark
// ladder of data/cow.off (level 4 = 1,114,370 vertices), back 30% along x fixed, detail-
// preserving stretch+bend energy — the system configs/boier-martin/solvers.yaml solves, built
// here from the energy and constraint objects themselves (no config).
#pragma once

#include <map>
#include <memory>
#include <string>

#include "fairshape/constraint/constraint_factories.h"
#include "fairshape/design/edit_assembly.h"
#include "fairshape/energy/local_quadratic.h"
#include "fairshape/experiment/components.h"
#include "fairshape/io/mesh_io.h"

namespace fairshape::bench {

struct CowEdit {
  std::unique_ptr<Energy> energy;
  std::unique_ptr<Constraint> back, nose;
  std::unique_ptr<MultiresSurface> hierarchy;
  EditLadder ladder;  // levels coarse..level
};

//! Cached per (level, coarse, solver): `solver` decides whether level operators come along.
inline const CowEdit& cow_edit(int level, int coarse, const std::string& solver = "cholesky") {
  static std::map<std::string, std::unique_ptr<CowEdit>> cache;
  const std::string key = std::to_string(level) + "/" + std::to_string(coarse) + "/" + solver;
  auto& slot = cache[key];
  if (slot) return *slot;
  auto e = std::make_unique<CowEdit>();
  e->energy = make_stretch_bend({0.1, 1.0}, StretchBendOf::Deformation, Backend::Optimized);
  e->back = prescribed_offset(VertexSelection::slab(0, 0.0, 0.3), Vec3::Zero(), -1, false, "back");
  e->nose = prescribed_offset(VertexSelection::nearest({0.5, 0.0, 0.0}), {0.15, 0.0, 0.08}, -1, false, "nose");
  e->hierarchy = std::make_unique<MultiresSurface>(read_mesh(std::string(FAIRSHAPE_SOURCE_DIR) + "/data/cow.off"),
                                                   SubdivisionOptions{}, level, Backend::Optimized);
  Config none;
  EditTerms terms;
  terms.energies = {{e->energy.get(), 1.0}};
  terms.constraints = {e->back.get(), e->nose.get()};
  terms.levels = components().solvers.create(solver, Backend::Optimized, none)->uses_levels();
  DesignConstraints placed;
  e->ladder = assemble_edit_ladder(terms, *e->hierarchy, coarse, level, placed);
  slot = std::move(e);
  return *slot;
}

}  // namespace fairshape::bench
