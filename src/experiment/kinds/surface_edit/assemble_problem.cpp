#include "experiment/kinds/surface_edit/assemble_problem.h"

#include "subdivision/subdivider.h"

namespace fairshape {

EditProblem assemble_problem(const RunSpec& spec, const MultiresSurface& h, int level, DesignConstraints& placed) {
  const SurfaceMesh& rest = h.mesh(level);
  const int n = rest.n_vertices();
  EditProblem p;
  p.H.resize(n, n);
  p.g = Eigen::MatrixXd::Zero(n, 3);
  for (const auto& e : spec.energies) {
    const SparseMatrix He = e.energy->hessian(rest, e.weight);
    if (e.energy->measures_positions() || spec.formulation == Formulation::Position)
      p.g -= He * rest.positions();  // the energy of P_rest + ΔP
    p.H += He;
  }
  if (level > 0 && spec.solver->uses_levels()) {  // the levels below, only a multilevel solver reads them
    auto ops = std::make_shared<LevelOperators>();
    for (int l = 0; l < level; ++l) ops->prolongation.push_back(h.subdivision_operator(l));
    for (int l = 0; l <= level; ++l) ops->singular.push_back(extraordinary_vertices(h.mesh(l), h.options().scheme));
    ops->reassemble = [&spec, &h](int l) {
      SparseMatrix H(h.mesh(l).n_vertices(), h.mesh(l).n_vertices());
      for (const auto& e : spec.energies) H += e.energy->hessian(h.mesh(l), e.weight);
      return H;
    };
    p.levels = ops;
  }
  const LevelMeshes mesh_at = [&h](int l) -> const SurfaceMesh& { return h.mesh(l); };
  for (const auto& c : spec.constraints) c.constraint->add_to(mesh_at, h.levels(), placed);
  p.constraints = propagate_constraints(h, level, placed);
  return p;
}

EditLadder assemble_ladder(const RunSpec& spec, const MultiresSurface& h, int coarse, int level,
                           DesignConstraints& placed) {
  EditLadder ladder;
  for (int l = coarse; l <= level; ++l) {
    DesignConstraints at_level;  // the same constraints, placed again: only the last set is kept
    ladder.problems.push_back(assemble_problem(spec, h, l, l == level ? placed : at_level));
    if (l < level) ladder.prolongations.push_back(h.subdivision_operator(l));
  }
  return ladder;
}

}  // namespace fairshape
