// The edit with rotation-aware details (beyond Boier-Martin et al.; energy/local_rotations.h):
// the constrained problem solved once with the energy of the deformation, then alternately the
// per-vertex rotations fitted to the result and the problem solved again with the turned rest
// derivatives as its linear term — one analysis of H and the constraints for every round.
#pragma once

#include <vector>

#include "fairshape/design/edit_assembly.h"
#include "fairshape/design/edit_solve.h"

namespace fairshape {

struct RotationAwareOptions {
  int iterations = 0;       // rounds of rotation fit + solve after the linear solve; 0: the linear energy
  double tolerance = 1e-4;  // stop when a round changes the deformation by less (relative)
};

struct RotationAwareSolution {
  EditSolution solution;  // termination max_iterations when the rounds ran out before the tolerance
  int rounds = 0;
  double last_change = 0;  // ‖Δ_k − Δ_{k−1}‖ / ‖Δ_k‖ of the last round
  double energy = 0;       // the objective (E_R + the other energies) at the solution
  std::vector<double> energy_history;  // the objective before each round, then at the solution
};

//! `rest`: the level `p` lives on. \throw InvalidInput when no energy turns its details
//! (only energies of the deformation do), or as solve_edit.
RotationAwareSolution solve_rotation_aware(const EditProblem& p, const std::vector<WeightedEnergy>& energies,
                                           const SurfaceMesh& rest, ConstraintMode mode, Solver& solver,
                                           Backend backend, const Config& qp_options, const RotationAwareOptions& o);

}  // namespace fairshape
