// The demo's detail-preserving edit (configs/demo.yaml, its --smoke size: Figure 2 of
// Boier-Martin et al.) through fairshape's libraries alone: the cow remeshed into a
// Catmull-Clark hierarchy with details, its back third fixed, its nose pulled, the paper's split
// (§4.3) with CHOLMOD on the free vertices. tests/cli/package_consumer.sh compares the result
// with the installed command line's run of the demo.
//   demo_edit COW.off BASE_FACES LEVELS OUT.obj
#include <fairshape/constraint/constraint_factories.h>
#include <fairshape/design/edit_assembly.h>
#include <fairshape/design/edit_solve.h>
#include <fairshape/energy/local_quadratic.h>
#include <fairshape/io/mesh_io.h>
#include <fairshape/remesh/remesh.h>
#include <fairshape/solver/solver.h>

#include <iostream>
#include <string>

int main(int argc, char** argv) {
  using namespace fairshape;
  if (argc != 5) {
    std::cerr << "usage: demo_edit COW.off BASE_FACES LEVELS OUT.obj\n";
    return 2;
  }
  try {
    RemeshOptions ropt;
    ropt.base_faces = std::stoi(argv[2]);
    ropt.levels = std::stoi(argv[3]);
    RemeshReport report;
    const MultiresSurface h = remesh(read_mesh(argv[1]), ropt, &report);
    const auto energy = make_stretch_bend({0.1, 1.0}, StretchBendOf::Deformation, Backend::Optimized);
    const auto back = prescribed_offset(VertexSelection::slab(0, 0.0, 0.3), Vec3::Zero());
    const auto nose = prescribed_offset(VertexSelection::nearest({0.5, 0.0, 0.0}), {0.15, 0.0, 0.08});
    EditTerms terms;
    terms.energies = {{energy.get(), 1.0}};
    terms.constraints = {back.get(), nose.get()};
    DesignConstraints placed;
    const EditProblem p = assemble_edit_problem(terms, h, h.levels(), placed);
    SolverRegistry solvers("solver");
    register_solvers(solvers);
    Config none;
    const auto cholesky = solvers.create("cholesky", Backend::Optimized, none);
    const EditSolution sol = solve_edit(p, ConstraintMode::Paper, *cholesky, Backend::Optimized);
    if (!is_success(sol.summary.termination)) {
      std::cerr << "demo_edit: " << to_string(sol.summary.termination) << ": " << sol.summary.message << "\n";
      return 3;
    }
    SurfaceMesh result = h.mesh(h.levels());
    result.positions() += MatrixX3(sol.delta);
    write_mesh(result, argv[4]);
  } catch (const std::exception& e) {
    std::cerr << "demo_edit: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
