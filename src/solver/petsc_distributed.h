// Distributed solves: a petsc_* solver with petsc.ranks > 1 hands its system to an MPI job
// (`<launcher> fairshape-mpi-solve JOB_DIR`, e.g. `mpirun -np 4 …`) through a job folder, and
// reads the solution back. The process that asks is never an MPI process itself, so it can be a
// worker of `fairshape run` (which forks and supervises) and a sweep can mix serial and
// distributed points. The job folder holds the system in PETSc's binary format (A.petsc,
// P<l>.petsc, near_null<k>.petsc, b<c>.petsc, x0_<c>.petsc), job.json (the settings and sizes),
// log.txt (the launcher's output) and, after the job, x<c>.petsc and result.json; the MPI
// program loads it with MatLoad, which shares the rows out across the ranks, so the same folder
// can be solved by hand on a cluster: `srun -n 64 fairshape-mpi-solve JOB_DIR`.
// In this version the system is assembled on one node and written once: set-up memory is one
// node's; the solve's memory is per rank (result.json, papers/boier-martin/README.md).
#pragma once

#include <string>
#include <vector>

#include "fairshape/core/types.h"
#include "fairshape/solver/petsc_settings.h"

namespace fairshape::petsc {

struct RankReport {
  int rank = 0;
  long long rows = 0, nonzeros = 0;  // its part of the fine operator
  double max_rss_mb = 0;             // the rank's peak resident memory
};

struct DistributedOutcome {
  std::vector<int> iterations;        // per column
  std::vector<std::string> reasons;   // KSPConvergedReason per column
  std::vector<double> error_estimates;  // per column, with error_tolerance (else −1)
  double setup_s = 0, solve_s = 0;    // inside the MPI job (KSPSetUp, the KSPSolves)
  double wall_s = 0;                  // the whole job: writing, launching, loading, solving, reading
  std::vector<RankReport> ranks;
};

//! Solves A x_c = b_c for every column (x holds the initial guess on entry, the solution after).
//! `prolongations[l]` (l ≥ 1) for petsc_mg, `near_null` columns (orthonormal) for petsc_gamg.
//! \throw SolverError with the job's log when the launch or the job fails.
DistributedOutcome solve_distributed(const Settings& s, const SparseMatrix& A, const std::vector<SparseMatrix>& prolongations,
                                     const Eigen::MatrixXd& near_null, const Eigen::MatrixXd& b, Eigen::MatrixXd& x);

//! The MPI program's main (experiments/cli/mpi_solve_main.cpp): argv[1] is the job folder.
int run_distributed_job(int argc, char** argv);

}  // namespace fairshape::petsc
