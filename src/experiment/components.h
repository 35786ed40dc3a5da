// Every registry of pluggable components, filled by register_all().
#pragma once

#include "constraint/constraint.h"
#include "energy/energy.h"
#include "solver/solver.h"

namespace fairshape {

struct Components {
  EnergyRegistry energies{"energy"};
  ConstraintRegistry constraints{"constraint"};
  SolverRegistry solvers{"solver"};
};

//! Registers every energy, constraint and solver, reference and optimized back ends.
void register_all(Components& c);
const Components& components();  // a process-wide instance, registered on first use

}  // namespace fairshape
