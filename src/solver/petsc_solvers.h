// The petsc_* solvers' registration (petsc_solver.cpp), for both back-end names: PETSc is the
// external peer, one implementation measured beside both of fairshape's. Built only with
// FAIRSHAPE_WITH_PETSC.
#pragma once

#include "fairshape/solver/solver.h"

namespace fairshape {

void register_petsc_solvers(SolverRegistry& r, Backend backend);

}  // namespace fairshape
