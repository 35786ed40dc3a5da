#include "fairshape/feature/sparse_measure.h"

#include <stdexcept>

#include "fairshape/feature/sparse_visible_profile.h"

namespace fairshape::feature {
namespace {

// The vertices whose limit point the sparse level cannot give (not complete) but the measure
// of curve c needs: within its measured reach (profile_measure.h), give or take twice the
// longest edge around them (a limit point lies in the hull of its one-ring; a moved control
// point, within the reach, moves the limit points of its one-ring).
int incomplete_near(const SurfaceMesh& patch, const std::vector<char>& complete, const BaseCurve& c, double reach) {
  int n = 0;
  for (int v = 0; v < patch.n_vertices(); ++v) {
    if (complete[static_cast<std::size_t>(v)]) continue;
    double edge = 0;
    patch.for_each_outgoing(v, [&](int h) { edge = std::max(edge, (patch.position(patch.to_vertex(h)) - patch.position(v)).norm()); });
    if (c.distance_to(patch.position(v)) < reach + 2 * edge) ++n;
  }
  return n;
}

}  // namespace

std::vector<SparseFeatureMeasure> measure_sparse_features(const AdaptiveEvaluation& a, int levels,
                                                          const SubdivisionOptions& opt, Backend backend) {
  const auto L = static_cast<std::size_t>(levels);
  if (a.levels.size() != L + 1 || a.feature_level.size() != a.curves.size())
    throw std::logic_error("sparse measure: the evaluation does not have " + std::to_string(levels) + " levels and its features' levels");
  // What was asked, as the uniform run's visible targets compose it (coarse levels first), on
  // the finest sparse level; what was achieved: its positions, and their limit points where
  // complete (an incomplete vertex keeps its control point: no displacement, it changes nothing;
  // the check below keeps such vertices away from every curve measured).
  const SparseVisibleTargets t = sparse_visible_targets(a.levels, a.unperturbed, a.curves, a.feature_level, opt, backend);
  const SurfaceMesh& mesh = t.finest.mesh;
  const int n = mesh.n_vertices();
  MatrixX3 achieved(n, 3);
  for (int v = 0; v < n; ++v) achieved.row(v) = a.levels[L].positions.row(t.finest.local[static_cast<std::size_t>(v)]);
  MatrixX3 achieved_limit = t.targets.limit_matrix * achieved;
  for (int v = 0; v < n; ++v)
    if (!t.complete[static_cast<std::size_t>(v)]) achieved_limit.row(v) = mesh.positions().row(v);

  std::vector<SparseFeatureMeasure> out(a.curves.size());
  std::vector<const BaseCurve*> all;
  for (const LevelOperator& op : t.operators)
    for (const BaseCurve& c : op.curves) all.push_back(&c);
  const VisibleTargets& x = t.targets;
  // The base mesh without features: the complete surface the thickness and size bounds of the
  // local scale are taken on (the finer levels hold only the features' regions).
  SparseLevel base = a.levels[0];
  if (!a.unperturbed.empty() && a.unperturbed[0].rows() == base.positions.rows()) base.positions = a.unperturbed[0];
  const SurfaceMesh whole = make_patch(base).mesh;
  for (std::size_t k = 0; k < t.operators.size(); ++k) {
    const LevelOperator& op = t.operators[k];
    const int below = levels - op.level;
    for (std::size_t j = 0; j < op.curves.size(); ++j) {
      const BaseCurve& curve = op.curves[j];
      std::vector<const BaseCurve*> others;
      for (const BaseCurve* c : all)
        if (c != &curve) others.push_back(c);
      SparseFeatureMeasure& m = out[static_cast<std::size_t>(op.ids[j])];
      m.fine = measure_on_mesh(mesh, x.fine[k], x.fine.back(), achieved, *op.surface, curve, others, below);
      m.scale = feature_scale(*op.surface, curve, whole);
      if (const int missing = incomplete_near(mesh, t.complete, curve, measured_reach(*op.surface, curve)); missing > 0) {
        m.limit_note = "limit not measured: " + std::to_string(missing) +
                       " finest vertices near the curve lack part of their one-ring on the sparse level (its support "
                       "is not refined completely)";
      } else {
        m.limit = measure_on_mesh(mesh, x.limit[k], x.limit.back(), achieved_limit, *op.surface, curve, others, below);
        m.limit_measured = true;
      }
    }
  }
  return out;
}

}  // namespace fairshape::feature
