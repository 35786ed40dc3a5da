// Boier-Martin et al.'s detail-preserving edit through fairshape's libraries alone: the cow
// subdivided twice (Catmull-Clark), its back third fixed, its nose pulled, the energy of the
// deformation minimized exactly (KKT). The same edit as the command line's
// `fairshape run` of tests/cli/package_consumer.sh, which compares the two results.
//   nose_pull COW.off OUT.obj
#include <fairshape/constraint/constraint_factories.h>
#include <fairshape/design/edit_assembly.h>
#include <fairshape/design/edit_solve.h>
#include <fairshape/energy/local_quadratic.h>
#include <fairshape/io/mesh_io.h>
#include <fairshape/solver/solver.h>
#include <fairshape/subdivision/multires_surface.h>

#include <iostream>

int main(int argc, char** argv) {
  using namespace fairshape;
  if (argc != 3) {
    std::cerr << "usage: nose_pull COW.off OUT.obj\n";
    return 2;
  }
  try {
    const MultiresSurface h(read_mesh(argv[1]), SubdivisionOptions{}, 2, Backend::Optimized);
    const auto energy = make_stretch_bend({0.1, 1.0}, StretchBendOf::Deformation, Backend::Optimized);
    const auto back = prescribed_offset(VertexSelection::slab(0, 0.0, 0.3), Vec3::Zero());
    const auto nose = prescribed_offset(VertexSelection::nearest({0.5, 0.0, 0.0}), {0.06, 0.0, 0.032});  // configs/smoke/cow_nose_pull.yaml's handle
    EditTerms terms;
    terms.energies = {{energy.get(), 1.0}};
    terms.constraints = {back.get(), nose.get()};
    DesignConstraints placed;
    const EditProblem p = assemble_edit_problem(terms, h, h.levels(), placed);
    SolverRegistry solvers("solver");
    register_solvers(solvers);
    Config none;
    const auto unused = solvers.create("cholesky", Backend::Optimized, none);  // KKT solves it whole
    const EditSolution sol = solve_edit(p, ConstraintMode::Kkt, *unused, Backend::Optimized);
    if (!is_success(sol.summary.termination)) {
      std::cerr << "nose_pull: " << to_string(sol.summary.termination) << ": " << sol.summary.message << "\n";
      return 3;
    }
    SurfaceMesh result = h.mesh(h.levels());
    result.positions() += MatrixX3(sol.delta);
    write_mesh(result, argv[2]);
    std::cout << "constraint residual " << sol.constraint_residual << "\n";
  } catch (const std::exception& e) {
    std::cerr << "nose_pull: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
