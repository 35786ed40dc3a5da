#include "fairshape/solver/solver.h"

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
}

}  // namespace fairshape::reference
