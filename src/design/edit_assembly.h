// The edit problem on one level of a hierarchy, or on a ladder of levels, from energies and
// constraints as objects (a config, a benchmark or a test builds them alike): H and the
// linear term from the weighted energies, the designer's constraints propagated from the
// levels they are placed on (Boier-Martin et al. §4.2, Table 1).
#pragma once

#include <vector>

#include "fairshape/constraint/constraint.h"
#include "fairshape/design/influence.h"
#include "fairshape/design/multilevel_edit.h"
#include "fairshape/energy/energy.h"
#include "fairshape/solver/level_operators.h"
#include "fairshape/subdivision/multires_surface.h"

namespace fairshape {

struct WeightedEnergy {
  const Energy* energy = nullptr;
  double weight = 1.0;
};

//! What an edit is made of. The pointers are not owned and must outlive the problems built
//! from them (a multilevel solver re-assembles coarse operators through them).
struct EditTerms {
  std::vector<WeightedEnergy> energies;
  std::vector<const Constraint*> constraints;
  //! Each constraint's region of influence (design/influence.h), index for index with
  //! `constraints`; empty: none has one of its own.
  std::vector<Influence> influences;
  const Influence& influence(std::size_t i) const {
    static const Influence none;
    return influences.empty() ? none : influences.at(i);
  }
  //! The energies measure positions P_rest + ΔP (the position formulation); energies whose
  //! measures_positions() is true always do.
  bool positions = false;
  //! Attach the levels below (LevelOperators) for a multilevel solver.
  bool levels = false;
  //! Normal constraints with rows `auto` are imposed by frame rows (constraint.h NormalRows):
  //! set when their tangent rows gave an answer with a reversed normal.
  bool frame_rows_for_auto_normals = false;
};

//! Appends constraint `c` as placed on the levels of `h` (with its subdivision rules) to `out`,
//! its normal rows resolved as `terms` says.
void place_constraint(const EditTerms& terms, const Constraint& c, const MultiresSurface& h, DesignConstraints& out);

//! Each vertex's star (the vertices of its faces, itself first) and its mean squared distance
//! to them: what multigrid's stiff-star patches need from a level (solver/level_operators.h).
VertexStars vertex_stars(const SurfaceMesh& mesh);

//! `placed` receives the constraints as placed on their own levels.
//! \throw InvalidInput for an empty energy list or a constraint that cannot be placed.
EditProblem assemble_edit_problem(const EditTerms& terms, const MultiresSurface& h, int level, DesignConstraints& placed);

//! Every check of assemble_edit_ladder(terms, h, coarse, level) that needs the hierarchy but
//! not H: each energy applies to the levels (valences), each constraint can be placed (its
//! level, vertices, selection, curve), the propagated constraints do not conflict and fix a
//! position. Cheap next to assembly, so validation makes it for every point of a sweep.
//! \throw InvalidInput as the assembly and solve_edit would.
void check_edit(const EditTerms& terms, const MultiresSurface& h, int coarse, int level);

//! Levels coarse..level; the last problem is assemble_edit_problem(level).
EditLadder assemble_edit_ladder(const EditTerms& terms, const MultiresSurface& h, int coarse, int level,
                                DesignConstraints& placed);

}  // namespace fairshape
