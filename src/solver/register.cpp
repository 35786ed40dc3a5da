#include "fairshape/solver/solver.h"

namespace fairshape {

std::unique_ptr<Solver> make_cholmod_cholesky(Config& cfg);
std::unique_ptr<Solver> make_multicolor_gauss_seidel(Config& cfg);
std::unique_ptr<Solver> make_multicolor_sor(Config& cfg);
std::unique_ptr<Solver> make_parallel_cg(Config& cfg);
std::unique_ptr<Solver> make_parallel_multigrid(Config& cfg);
std::unique_ptr<Solver> make_parallel_multigrid_cg(Config& cfg);

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
#else
  (void)r;
#endif
}

}  // namespace fairshape
