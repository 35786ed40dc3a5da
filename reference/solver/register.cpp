#include "fairshape/solver/solver.h"
#if FAIRSHAPE_WITH_PETSC
#include "fairshape/solver/petsc_solvers.h"
#endif

namespace fairshape::reference {

std::unique_ptr<Solver> make_simplicial_cholesky(Config& cfg);
std::unique_ptr<Solver> make_gauss_seidel(Config& cfg);
std::unique_ptr<Solver> make_sor(Config& cfg);
std::unique_ptr<Solver> make_serial_cg(Config& cfg);
std::unique_ptr<Solver> make_multigrid(Config& cfg);
std::unique_ptr<Solver> make_multigrid_cg(Config& cfg);

void register_solvers(SolverRegistry& r) {
  r.add("cholesky", Backend::Reference, "sparse Cholesky, Eigen SimplicialLDLT", make_simplicial_cholesky);
  r.add("gauss_seidel", Backend::Reference, "lexicographic Gauss-Seidel sweeps", make_gauss_seidel);
  r.add("sor", Backend::Reference, "lexicographic SOR with relaxation sor.omega", make_sor);
  r.add("conjugate_gradient", Backend::Reference, "Jacobi-preconditioned CG, serial products", make_serial_cg);
  r.add("multigrid", Backend::Reference, "multigrid on the hierarchy's levels, serial Eigen kernels", make_multigrid);
  r.add("multigrid_cg", Backend::Reference, "CG preconditioned by one symmetric multigrid cycle, serial",
        make_multigrid_cg);
#if FAIRSHAPE_WITH_PETSC
  fairshape::register_petsc_solvers(r, Backend::Reference);  // the same external peer under both names
#endif
}

}  // namespace fairshape::reference
