// An edit whose constraints each have their own region of influence (Boier-Martin et al.,
// "Detail-preserving variational surface design with multiresolution constraints", §4.2;
// the region is defined in design/influence.h).
//
// Constraints are grouped by influence level and solved in passes, coarse to fine. Pass k:
//   unknowns     the level-k vertices of its constraints' regions (the whole level for a
//                constraint without rings); every other level-k vertex keeps its place;
//   energy       the energy of the whole deformation so far, E(Δ_prev + δ), on level k's H:
//                ½ δᵀHδ − (g − HΔ_prev)ᵀδ;
//   constraints  its own, plus every constraint of a coarser pass and every fixed one, each
//                propagated to level k (Table 1) with what is still missing from the current
//                shape as its target — so a later pass neither undoes an earlier one nor a
//                fixed region; rows that reach none of the unknowns cannot move and are left;
//   result       δ added to level k, the finer levels re-synthesized with their local details;
//                repeated with the targets measured again until the surface meets them (the
//                details' frames turn with the edit, which the linear rows do not see).
// A constraint given on level j is met on level j (its vertex or limit point), so its influence
// level must be ≤ j. With every constraint on the edit level and no rings this is one pass
// over the whole level: the plain single-level edit.
#pragma once

#include <vector>

#include "fairshape/design/edit_assembly.h"
#include "fairshape/design/edit_solve.h"
#include "fairshape/design/influence.h"

namespace fairshape {

//! A pass stops when what its constraints miss on the surface is within this × the model's
//! bounding-box diagonal (problem.constraint_tolerance), or when its rounds stop gaining; a
//! result that misses by more ends constraints_unmet. The floor is not rounding: a fixed vertex
//! next to a coarse pass's region keeps its linear row, but its detail's frame turns with its
//! moved neighbours (measured: 3e-8 of the model's size on the cow's nose, level-0 region, and
//! 1.3e-7 on the 200-face remesh after the remesher's guarded moves — so 1e-6, a micrometre on
//! a metre-sized model).
constexpr double kDefaultConstraintTolerance = 1e-6;

struct RegionalPass {
  int level = 0;
  int rounds = 0;            // solves until the surface met the pass's constraints
  int unknowns = 0;          // vertices of level `level` that moved freely
  int level_vertices = 0;
  double surface_fraction = 0;  // of the finest level's vertices, inside this pass's region
  Eigen::VectorXi reached;      // 1 for the finest-level vertices of this pass's region
  SolveSummary summary;
  double analyze_s = 0, solve_s = 0;
};

struct RegionalEditResult {
  MultiresSurface edited;  // the hierarchy after every pass (the finer levels with local details)
  std::vector<RegionalPass> passes;
  DesignConstraints placed;  // every constraint as placed on its own level
  //! Per finest-level vertex: 1 + the first (coarsest) pass whose region reaches it; 0 outside every region.
  Eigen::VectorXi region;
  SolveSummary summary;  // the passes': iterations added, the first failure's termination
  double analyze_s = 0, solve_s = 0;
  double constraint_violation = 0;  // ‖what is still missing‖ over every constraint, on the final shape
  //! Largest finest-level difference outside every region from the hierarchy re-synthesized
  //! without an edit: 0 by construction.
  double outside_region_move = 0;
};

//! True when some constraint has an influence level or rings of its own.
bool is_regional(const EditTerms& terms);

//! The checks of solve_regional_edit that need the hierarchy but no H: influence levels exist
//! and are not finer than the level their constraint is given on, a bounded region is not
//! asked of a solver that needs the whole level (multigrid), and each pass's constraints can
//! be placed and do not conflict. \throw InvalidInput naming the constraint.
void check_regional_edit(const EditTerms& terms, const MultiresSurface& h, int edit_level, const Solver& solver,
                         ConstraintMode mode);

//! \throw InvalidInput as check_regional_edit; SolverError from a pass's solve.
RegionalEditResult solve_regional_edit(const EditTerms& terms, const MultiresSurface& rest, int edit_level,
                                       ConstraintMode mode, Solver& solver, Backend backend, const Config& qp_options,
                                       double tolerance = kDefaultConstraintTolerance);

}  // namespace fairshape
