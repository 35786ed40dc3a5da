// Every registry of pluggable components, filled by register_all().
#pragma once

#include "fairshape/constraint/constraint.h"
#include "fairshape/energy/energy.h"
#include "fairshape/solver/solver.h"

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
