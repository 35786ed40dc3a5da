// The edit problem of a run on one level of its hierarchy, or on a ladder of levels: H and
// the linear term from the configured energies, the designer's constraints propagated from
// the levels they are placed on (Boier-Martin et al. §4.2, Table 1).
#pragma once

#include "design/multilevel_edit.h"
#include "experiment/run_spec.h"
#include "subdivision/multires_surface.h"

namespace fairshape {

//! `placed` receives the constraints as placed on their own levels. The levels below come
//! along (LevelOperators) only when the run's solver is multilevel.
EditProblem assemble_problem(const RunSpec& spec, const MultiresSurface& h, int level, DesignConstraints& placed);

//! Levels coarse..level; the last problem is assemble_problem(level).
EditLadder assemble_ladder(const RunSpec& spec, const MultiresSurface& h, int coarse, int level,
                           DesignConstraints& placed);

}  // namespace fairshape
