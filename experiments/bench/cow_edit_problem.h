// The edit every issue-5 benchmark solves: the Figure 2 nose handle on the Catmull-Clark
// ladder of data/cow.off (level 4 = 1,114,370 vertices), back 30% along x fixed, detail-
// preserving stretch+bend energy; built through the same config path as
// configs/boier-martin/solvers.yaml, so the benchmark and the sweep solve one system.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "experiment/kinds/surface_edit/assemble_problem.h"
#include "experiment/components.h"
#include "io/mesh_io.h"
#include "experiment/run_spec.h"

namespace fairshape::bench {

struct CowEdit {
  RunSpec spec;
  std::unique_ptr<MultiresSurface> hierarchy;
  EditLadder ladder;  // levels coarse..level
};

//! Cached per (level, coarse, solver): `solver` decides whether level operators come along.
inline const CowEdit& cow_edit(int level, int coarse, const std::string& solver = "cholesky") {
  static std::map<std::string, std::unique_ptr<CowEdit>> cache;
  const std::string key = std::to_string(level) + "/" + std::to_string(coarse) + "/" + solver;
  auto& slot = cache[key];
  if (slot) return *slot;
  const std::string yaml = R"(
name: bench
input: { mesh: data/cow.off, representation: catmull-clark, levels: )" + std::to_string(level) + R"( }
energy: [ { type: detail_preserving, alpha: 0.1, beta: 1.0 } ]
constraints:
  - { type: fixed, region: { axis: x, from: 0.0, to: 0.3 } }
  - { type: position, nearest: [0.5, 0.0, 0.0], offset: [0.15, 0.0, 0.08] }
solver: { type: )" + solver + R"( }
)";
  auto e = std::make_unique<CowEdit>();
  e->spec = RunSpec::from_config(YAML::Load(yaml), components(), {FAIRSHAPE_SOURCE_DIR});
  e->hierarchy = std::make_unique<MultiresSurface>(read_mesh(e->spec.mesh_path), SubdivisionOptions{}, level,
                                                   Backend::Optimized);
  DesignConstraints placed;
  e->ladder = assemble_ladder(e->spec, *e->hierarchy, coarse, level, placed);
  slot = std::move(e);
  return *slot;
}

}  // namespace fairshape::bench
