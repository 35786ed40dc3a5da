#include "fairshape/feature/sparse_measure.h"

#include <stdexcept>

#include "fairshape/subdivision/limit.h"

namespace fairshape::feature {
namespace {

// The vertices whose limit point the sparse level cannot give (not complete) but the measure
// of curve c needs: within its reach, give or take twice the longest edge around them (a limit
// point lies in the hull of its one-ring; the requested displacement is nonzero within the
// reach, and a moved control point, within the reach, moves the limit points of its one-ring).
int incomplete_near(const SurfaceMesh& patch, const std::vector<char>& complete, const BaseCurve& c) {
  int n = 0;
  for (int v = 0; v < patch.n_vertices(); ++v) {
    if (complete[static_cast<std::size_t>(v)]) continue;
    double edge = 0;
    patch.for_each_outgoing(v, [&](int h) { edge = std::max(edge, (patch.position(patch.to_vertex(h)) - patch.position(v)).norm()); });
    if (c.distance_to(patch.position(v)) < c.reach() + 2 * edge) ++n;
  }
  return n;
}

}  // namespace

std::vector<SparseFeatureMeasure> measure_sparse_features(const AdaptiveEvaluation& a, int levels,
                                                          const SubdivisionOptions& opt, Backend backend) {
  const auto L = static_cast<std::size_t>(levels);
  if (a.levels.size() <= L || a.unperturbed.size() <= L || a.unperturbed[L].rows() != a.levels[L].positions.rows())
    throw std::logic_error("sparse measure: the finest level's positions before the features are missing");
  const SparseLevel& S = a.levels[L];
  // The finest level as the patch the features were applied on (positions before them), the
  // achieved positions beside it, and what was asked: the profile as a displacement
  // (OffsetMeaning::Displacement), as the uniform run's visible targets take it.
  SparseLevel before = S;
  before.positions = a.unperturbed[L];
  const SparsePatch patch = make_patch(before);
  const SurfaceMesh& mesh = patch.mesh;
  const int n = mesh.n_vertices();
  const MatrixX3& reference = mesh.positions();
  MatrixX3 achieved(n, 3);
  std::vector<char> complete(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v) {
    const int local = patch.local[static_cast<std::size_t>(v)];
    achieved.row(v) = S.positions.row(local);
    complete[static_cast<std::size_t>(v)] = S.complete[static_cast<std::size_t>(local)];
  }
  const TriangleSurface drawn(mesh, loop_limit_normals(mesh));
  const MatrixX3 requested = reference + displace_points(drawn, a.curves, reference, backend).dense(n);
  // Limit points: a complete vertex's limit row on the patch is the uniform level's (its whole
  // one-ring, in the same fan). An incomplete vertex gets no limit point: its three positions are
  // its control point (no displacement, so it changes nothing; the check below keeps such
  // vertices away from every curve measured).
  const SparseMatrix limit = limit_matrix(mesh, opt);
  MatrixX3 reference_limit = limit * reference, achieved_limit = limit * achieved;
  for (int v = 0; v < n; ++v)
    if (!complete[static_cast<std::size_t>(v)]) reference_limit.row(v) = achieved_limit.row(v) = reference.row(v);
  MatrixX3 requested_limit = reference_limit + displace_points(drawn, a.curves, reference_limit, backend).dense(n);
  for (int v = 0; v < n; ++v)
    if (!complete[static_cast<std::size_t>(v)]) requested_limit.row(v) = reference.row(v);

  std::vector<SparseFeatureMeasure> out;
  for (const BaseCurve& curve : a.curves) {
    std::vector<const BaseCurve*> others;
    for (const BaseCurve& c : a.curves)
      if (&c != &curve) others.push_back(&c);
    SparseFeatureMeasure m;
    m.fine = measure_on_mesh(mesh, reference, requested, achieved, drawn, curve, others);
    if (const int missing = incomplete_near(mesh, complete, curve); missing > 0) {
      m.limit_note = "limit not measured: " + std::to_string(missing) +
                     " finest vertices near the curve lack part of their one-ring on the sparse level (its support "
                     "is not refined completely)";
    } else {
      m.limit = measure_on_mesh(mesh, reference_limit, requested_limit, achieved_limit, drawn, curve, others);
      m.limit_measured = true;
    }
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace fairshape::feature
