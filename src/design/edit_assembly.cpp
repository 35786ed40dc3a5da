#include "fairshape/design/edit_assembly.h"

#include <algorithm>

#include "fairshape/design/multires_constraints.h"
#include "fairshape/energy/divided_differences.h"
#include "fairshape/subdivision/subdivider.h"

namespace fairshape {

VertexStars vertex_stars(const SurfaceMesh& mesh) {
  VertexStars s;
  const int n = mesh.n_vertices();
  s.offsets.reserve(static_cast<std::size_t>(n) + 1);
  s.size2.assign(static_cast<std::size_t>(n), 0.0);
  s.offsets.push_back(0);
  std::vector<int> star;
  for (int v = 0; v < n; ++v) {
    // The ring the energy's local fit is taken over (its faces' vertices), each vertex once.
    star.assign(1, v);
    if (!mesh.is_isolated(v))
      for (int u : ordered_one_ring(mesh, v))
        if (std::find(star.begin(), star.end(), u) == star.end()) star.push_back(u);
    double sum = 0;
    for (std::size_t k = 1; k < star.size(); ++k) sum += (mesh.position(star[k]) - mesh.position(v)).squaredNorm();
    s.size2[static_cast<std::size_t>(v)] = star.size() > 1 ? sum / static_cast<double>(star.size() - 1) : 0.0;
    s.ids.insert(s.ids.end(), star.begin(), star.end());
    s.offsets.push_back(static_cast<int>(s.ids.size()));
  }
  return s;
}

EditProblem assemble_edit_problem(const EditTerms& terms, const MultiresSurface& h, int level, DesignConstraints& placed) {
  if (terms.energies.empty()) throw InvalidInput("edit: no energy term");
  const SurfaceMesh& rest = h.mesh(level);
  const int n = rest.n_vertices();
  EditProblem p;
  p.H.resize(n, n);
  p.g = Eigen::MatrixXd::Zero(n, 3);
  for (const WeightedEnergy& e : terms.energies) {
    SparseMatrix He = e.energy->hessian(rest, e.weight);
    if (e.energy->measures_positions() || terms.positions) {  // the energy of P_rest + ΔP
      const Eigen::MatrixXd HP = He * rest.positions();
      p.g -= HP;
      p.energy_at_rest += 0.5 * (rest.positions().transpose() * HP).trace();
    }
    // The first term is moved in, not added to an empty H: the sum's temporary and its
    // assignment held three copies of H at once (1 GB at level 4, the set-up's largest spike).
    if (p.H.nonZeros() == 0) p.H = std::move(He);
    else p.H += He;
  }
  if (level > 0 && terms.levels) {
    auto ops = std::make_shared<LevelOperators>();
    for (int l = 0; l < level; ++l) ops->prolongation.push_back(h.subdivision_operator(l));
    for (int l = 0; l <= level; ++l) ops->singular.push_back(extraordinary_vertices(h.mesh(l), h.options().scheme));
    ops->stars = [&h](int l) { return vertex_stars(h.mesh(l)); };
    ops->positions = rest.positions();
    ops->reassemble = [energies = terms.energies, &h](int l) {
      SparseMatrix H(h.mesh(l).n_vertices(), h.mesh(l).n_vertices());
      for (const WeightedEnergy& e : energies) H += e.energy->hessian(h.mesh(l), e.weight);
      return H;
    };
    p.levels = ops;
  }
  for (const Constraint* c : terms.constraints) place_constraint(terms, *c, h, placed);
  p.constraints = propagate_constraints(h, level, placed);
  return p;
}

void place_constraint(const EditTerms& terms, const Constraint& c, const MultiresSurface& h, DesignConstraints& out) {
  const LevelMeshes mesh_at = [&h](int l) -> const SurfaceMesh& { return h.mesh(l); };
  const std::size_t first = out.normals.size();
  c.add_on_surface(mesh_at, h.levels(), h.options(), out);
  if (!terms.frame_rows_for_auto_normals) return;
  for (std::size_t i = first; i < out.normals.size(); ++i)
    if (out.normals[i].rows == NormalRows::Auto) out.normals[i].rows = NormalRows::Frame;
}

void check_edit(const EditTerms& terms, const MultiresSurface& h, int coarse, int level) {
  if (terms.energies.empty()) throw InvalidInput("edit: no energy term");
  DesignConstraints placed;
  for (const Constraint* c : terms.constraints) place_constraint(terms, *c, h, placed);
  for (int l = coarse; l <= level; ++l) {
    for (const WeightedEnergy& e : terms.energies) e.energy->check_applicable(h.mesh(l));
    check_constraints(h, l, placed);
  }
}

EditLadder assemble_edit_ladder(const EditTerms& terms, const MultiresSurface& h, int coarse, int level,
                                DesignConstraints& placed) {
  EditLadder ladder;
  for (int l = coarse; l <= level; ++l) {
    DesignConstraints at_level;  // the same constraints, placed again: only the last set is kept
    ladder.problems.push_back(assemble_edit_problem(terms, h, l, l == level ? placed : at_level));
    if (l < level) ladder.prolongations.push_back(h.subdivision_operator(l));
  }
  return ladder;
}

}  // namespace fairshape
