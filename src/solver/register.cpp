#include "fairshape/solver/solver.h"
#if FAIRSHAPE_WITH_PETSC
#include "fairshape/solver/petsc_settings.h"
#include "fairshape/solver/petsc_solvers.h"
#endif

namespace fairshape {

std::unique_ptr<Solver> make_cholmod_cholesky(Config& cfg);
std::unique_ptr<Solver> make_multicolor_gauss_seidel(Config& cfg);
std::unique_ptr<Solver> make_multicolor_sor(Config& cfg);
std::unique_ptr<Solver> make_parallel_cg(Config& cfg);
std::unique_ptr<Solver> make_parallel_multigrid(Config& cfg);
std::unique_ptr<Solver> make_parallel_multigrid_cg(Config& cfg);
#if FAIRSHAPE_WITH_PETSC
std::unique_ptr<Solver> make_petsc_solver(Config& cfg, petsc::Preconditioner preconditioner);

void register_petsc_solvers(SolverRegistry& r, Backend backend) {
  using petsc::Preconditioner;
  r.add("petsc_mg", backend,
        "PETSc CG + PCMG over fairshape's restricted prolongations (Galerkin coarse operators, SSOR smoothing); "
        "petsc.ranks > 1: an MPI job",
        [](Config& cfg) { return make_petsc_solver(cfg, Preconditioner::Mg); });
  r.add("petsc_gamg", backend, "PETSc CG + GAMG smoothed aggregation (near-null space: constants and linear functions)",
        [](Config& cfg) { return make_petsc_solver(cfg, Preconditioner::Gamg); });
  r.add("petsc_boomeramg", backend, "PETSc CG + hypre BoomerAMG (PCHYPRE)",
        [](Config& cfg) { return make_petsc_solver(cfg, Preconditioner::BoomerAmg); });
}
#endif

void register_solvers(SolverRegistry& r) {
#if FAIRSHAPE_WITH_TBB  // without TBB only the reference solvers (reference/solver) exist
  r.add("cholesky", Backend::Optimized, "sparse Cholesky, CHOLMOD supernodal LLᵀ (factored once)",
        make_cholmod_cholesky);
  r.add("gauss_seidel", Backend::Optimized, "multicolour Gauss-Seidel, TBB-parallel per colour",
        make_multicolor_gauss_seidel);
  r.add("sor", Backend::Optimized, "multicolour SOR with relaxation sor.omega, TBB-parallel", make_multicolor_sor);
  r.add("conjugate_gradient", Backend::Optimized, "Jacobi-preconditioned CG, TBB-parallel products",
        make_parallel_cg);
  r.add("multigrid", Backend::Optimized,
        "multigrid on the hierarchy's levels (V/W/FMG, Galerkin or re-assembled coarse operators), TBB kernels",
        make_parallel_multigrid);
  r.add("multigrid_cg", Backend::Optimized, "CG preconditioned by one symmetric multigrid cycle, TBB kernels",
        make_parallel_multigrid_cg);
#if FAIRSHAPE_WITH_PETSC
  register_petsc_solvers(r, Backend::Optimized);
#endif
#else
  (void)r;
#endif
}

}  // namespace fairshape
