// fairshape-mpi-solve JOB_DIR: the MPI program of distributed petsc_* solves, started by the
// solver (`mpirun -np N fairshape-mpi-solve JOB_DIR`) or by hand on a cluster (petsc_distributed.h).
#include "fairshape/solver/petsc_distributed.h"

int main(int argc, char** argv) { return fairshape::petsc::run_distributed_job(argc, argv); }
