#include "fairshape/feature/visible_profile.h"

#include <Eigen/SparseCholesky>

#include "fairshape/subdivision/limit.h"

namespace fairshape::feature {

const NameTable<ProfileTarget>& profile_target_names() {
  static const NameTable<ProfileTarget> t{
      {ProfileTarget::DrawnLevel, "drawn_level"}, {ProfileTarget::Finest, "finest"}, {ProfileTarget::Limit, "limit"}};
  return t;
}

VisibleTargets compose_visible_targets(const SurfaceMesh& finest_original, const SubdivisionOptions& opt,
                                       const std::vector<LevelOperator>& operators, Backend backend) {
  VisibleTargets t;
  t.limit_matrix = limit_matrix(finest_original, opt);
  t.fine.push_back(finest_original.positions());
  t.limit.push_back(t.limit_matrix * finest_original.positions());
  const int n = finest_original.n_vertices();
  for (const LevelOperator& op : operators) {
    t.fine.push_back(t.fine.back() + displace_points(*op.surface, op.curves, t.fine.back(), backend).dense(n));
    t.limit.push_back(t.limit.back() + displace_points(*op.surface, op.curves, t.limit.back(), backend).dense(n));
  }
  return t;
}

MatrixX3 control_points_for_limit(const SurfaceMesh& mesh, const SparseMatrix& limit_matrix, const MatrixX3& reference,
                                  const MatrixX3& limit_displacement, int rings) {
  const MatrixX3& rhs_all = limit_displacement;
  const int n = mesh.n_vertices();
  // Unknowns: the vertices whose limit point moves, grown by `rings`; rows: one ring more (every
  // limit point whose stencil reaches an unknown).
  std::vector<int> index(static_cast<std::size_t>(n), -1), unknowns, frontier;
  for (int v = 0; v < n; ++v)
    if (rhs_all.row(v).squaredNorm() > 0) frontier.push_back(v);
  if (frontier.empty()) return reference;
  std::vector<char> in(static_cast<std::size_t>(n), 0);
  for (int v : frontier) in[static_cast<std::size_t>(v)] = 1;
  std::vector<int> grown = frontier, rows;
  for (int ring = 0; ring <= rings; ++ring) {
    if (ring == rings) unknowns = grown;  // the last ring grown below is rows only
    std::vector<int> next;
    for (int v : frontier)
      mesh.for_each_outgoing(v, [&](int h) {
        const int w = mesh.to_vertex(h);
        if (!in[static_cast<std::size_t>(w)]) in[static_cast<std::size_t>(w)] = 1, next.push_back(w);
      });
    grown.insert(grown.end(), next.begin(), next.end());
    frontier = std::move(next);
  }
  rows = grown;
  for (std::size_t k = 0; k < unknowns.size(); ++k) index[static_cast<std::size_t>(unknowns[k])] = static_cast<int>(k);
  using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  const RowMajor by_rows = limit_matrix;
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (RowMajor::InnerIterator it(by_rows, rows[r]); it; ++it)
      if (const int c = index[static_cast<std::size_t>(it.col())]; c >= 0)
        entries.emplace_back(static_cast<int>(r), c, it.value());
  SparseMatrix A(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(unknowns.size()));
  A.setFromTriplets(entries.begin(), entries.end());
  MatrixX3 b(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t r = 0; r < rows.size(); ++r) b.row(static_cast<Eigen::Index>(r)) = rhs_all.row(rows[r]);
  const SparseMatrix At = A.transpose();
  const Eigen::SimplicialLDLT<SparseMatrix> solver(SparseMatrix(At * A));
  if (solver.info() != Eigen::Success)
    throw SolverError("the limit-surface fit of the features: the normal equations on " +
                      std::to_string(unknowns.size()) + " control points are singular");
  const MatrixX3 C = solver.solve(At * b);
  if (!C.allFinite()) throw SolverError("the limit-surface fit of the features is not finite");
  MatrixX3 X = reference;
  for (std::size_t k = 0; k < unknowns.size(); ++k) X.row(unknowns[k]) += C.row(static_cast<Eigen::Index>(k));
  return X;
}

}  // namespace fairshape::feature
