#include "fairshape/feature/sparse_visible_profile.h"

#include <stdexcept>

namespace fairshape::feature {

SparseVisibleTargets sparse_visible_targets(const std::vector<SparseLevel>& levels, const std::vector<MatrixX3>& unperturbed,
                                            const std::vector<BaseCurve>& curves, const std::vector<int>& curve_level,
                                            const SubdivisionOptions& opt, Backend backend) {
  if (levels.empty()) throw std::logic_error("sparse visible targets: no levels");
  const int L = static_cast<int>(levels.size()) - 1;
  SparseVisibleTargets t;
  // Each featured level as its operator: the patch before its features (the curves were built
  // on it: face i of the patch is present face i).
  for (int l = 0; l <= L; ++l) {
    LevelOperator op;
    op.level = l;
    for (std::size_t i = 0; i < curves.size(); ++i)
      if (curve_level[i] == l) op.ids.push_back(static_cast<int>(i)), op.curves.push_back(curves[i]);
    if (op.ids.empty()) continue;
    const auto ul = static_cast<std::size_t>(l);
    if (unperturbed.size() <= ul || unperturbed[ul].rows() != levels[ul].positions.rows())
      throw std::logic_error("sparse visible targets: level " + std::to_string(l) + " lacks its positions before its features");
    SparseLevel before = levels[ul];
    before.positions = unperturbed[ul];
    op.mesh = std::make_shared<SurfaceMesh>(make_patch(before).mesh);
    op.surface = std::make_shared<TriangleSurface>(*op.mesh, loop_limit_normals(*op.mesh));
    t.operators.push_back(std::move(op));
  }
  const SparseLevel& S = levels.back();
  if (S.original.rows() != S.positions.rows())
    throw std::logic_error("sparse visible targets: the finest level lacks its positions without features");
  SparseLevel original = S;
  original.positions = S.original;
  t.finest = make_patch(original);
  const int n = t.finest.mesh.n_vertices();
  t.complete.resize(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v) t.complete[static_cast<std::size_t>(v)] = S.complete[static_cast<std::size_t>(t.finest.local[v])];
  t.targets = compose_visible_targets(t.finest.mesh, opt, t.operators, backend);
  // An incomplete vertex's limit row on the patch is not the uniform one: it keeps its control
  // point (no displacement) in every limit target.
  for (int v = 0; v < n; ++v)
    if (!t.complete[static_cast<std::size_t>(v)])
      for (MatrixX3& x : t.targets.limit) x.row(v) = t.finest.mesh.positions().row(v);
  return t;
}

}  // namespace fairshape::feature
