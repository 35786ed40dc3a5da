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
  t.limit_by_rows = t.limit_matrix;
  t.fine.push_back(finest_original.positions());
  t.limit.push_back(t.limit_matrix * finest_original.positions());
  const int n = finest_original.n_vertices();
  for (const LevelOperator& op : operators) {
    t.fine.push_back(t.fine.back() + displace_points(*op.surface, op.curves, t.fine.back(), backend).dense(n));
    t.limit.push_back(t.limit.back() + displace_points(*op.surface, op.curves, t.limit.back(), backend).dense(n));
  }
  return t;
}

namespace {

using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// `from` grown by one ring on `mesh`, the new vertices marked in `in` and appended to `grown`.
std::vector<int> grow_ring(const SurfaceMesh& mesh, const std::vector<int>& from, std::vector<char>& in, std::vector<int>& grown) {
  std::vector<int> next;
  for (int v : from)
    mesh.for_each_outgoing(v, [&](int h) {
      const int w = mesh.to_vertex(h);
      if (!in[static_cast<std::size_t>(w)]) in[static_cast<std::size_t>(w)] = 1, next.push_back(w);
    });
  grown.insert(grown.end(), next.begin(), next.end());
  return next;
}

// The least-squares fit for the vertices `moving` (nonzero limit displacement): unknowns are
// they and `rings` rings around them, rows one ring more (every limit point whose stencil
// reaches an unknown). Adds the solution to X's unknown rows; returns the unknowns.
std::vector<int> fit_block(const SurfaceMesh& mesh, const RowMajor& by_rows, const LimitDisplacement& rhs_all,
                           const std::vector<int>& moving, int rings, MatrixX3& X) {
  const int n = mesh.n_vertices();
  std::vector<int> unknowns, frontier = moving;
  if (frontier.empty()) return unknowns;
  std::vector<char> in(static_cast<std::size_t>(n), 0);
  for (int v : frontier) in[static_cast<std::size_t>(v)] = 1;
  std::vector<int> grown = frontier;
  for (int ring = 0; ring <= rings; ++ring) {
    if (ring == rings) unknowns = grown;  // the last ring grown below is rows only
    frontier = grow_ring(mesh, frontier, in, grown);
  }
  const std::vector<int>& rows = grown;
  std::vector<int> index(static_cast<std::size_t>(n), -1);
  for (std::size_t k = 0; k < unknowns.size(); ++k) index[static_cast<std::size_t>(unknowns[k])] = static_cast<int>(k);
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (RowMajor::InnerIterator it(by_rows, rows[r]); it; ++it)
      if (const int c = index[static_cast<std::size_t>(it.col())]; c >= 0) entries.emplace_back(static_cast<int>(r), c, it.value());
  SparseMatrix A(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(unknowns.size()));
  A.setFromTriplets(entries.begin(), entries.end());
  MatrixX3 b(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t r = 0; r < rows.size(); ++r) b.row(static_cast<Eigen::Index>(r)) = rhs_all(rows[r]).transpose();
  const SparseMatrix At = A.transpose();
  const Eigen::SimplicialLDLT<SparseMatrix> solver(SparseMatrix(At * A));
  if (solver.info() != Eigen::Success)
    throw SolverError("the limit-surface fit of the features: the normal equations on " +
                      std::to_string(unknowns.size()) + " control points are singular");
  const MatrixX3 C = solver.solve(At * b);
  if (!C.allFinite()) throw SolverError("the limit-surface fit of the features is not finite");
  for (std::size_t k = 0; k < unknowns.size(); ++k) X.row(unknowns[k]) += C.row(static_cast<Eigen::Index>(k));
  return unknowns;
}

std::vector<int> nonzero_rows(const MatrixX3& m) {
  std::vector<int> out;
  for (int v = 0; v < static_cast<int>(m.rows()); ++v)
    if (m.row(v).squaredNorm() > 0) out.push_back(v);
  return out;
}

}  // namespace

MatrixX3 control_points_for_limit(const SurfaceMesh& mesh, const SparseMatrix& limit_matrix, const MatrixX3& reference,
                                  const MatrixX3& limit_displacement, int rings) {
  MatrixX3 X = reference;
  const LimitDisplacement rhs = [&](int v) { return Vec3(limit_displacement.row(v).transpose()); };
  (void)fit_block(mesh, RowMajor(limit_matrix), rhs, nonzero_rows(limit_displacement), rings, X);
  return X;
}

std::vector<int> refit_control_points_for_limit(const SurfaceMesh& mesh, const RowMajor& limit_by_rows, const MatrixX3& reference,
                                                const LimitDisplacement& limit_displacement, const std::vector<char>& was_moving,
                                                const std::vector<int>& changed, MatrixX3& X, int rings) {
  const int n = mesh.n_vertices();
  const auto moving_now = [&](int v) { return limit_displacement(v).squaredNorm() > 0; };
  const auto moving_either = [&](int v) { return moving_now(v) || was_moving[static_cast<std::size_t>(v)]; };
  // The blocks of the fit that meet the change: vertices moving before or now, joined when they
  // lie within 2 rings + 2 of each other (their unknowns then share a row), from the changed
  // rows on. Blocks apart from them keep their solution (their equations are untouched).
  std::vector<char> in_block(static_cast<std::size_t>(n), 0);
  std::vector<int> block, frontier;
  for (int v : changed)
    if (moving_either(v) && !in_block[static_cast<std::size_t>(v)]) in_block[static_cast<std::size_t>(v)] = 1, frontier.push_back(v);
  std::vector<int> stamp(static_cast<std::size_t>(n), -1);
  for (int round = 0; !frontier.empty(); ++round) {
    block.insert(block.end(), frontier.begin(), frontier.end());
    std::vector<int> reached = frontier, next, layer = frontier;
    for (int v : frontier) stamp[static_cast<std::size_t>(v)] = round;
    for (int ring = 0; ring < 2 * rings + 2; ++ring) {
      std::vector<int> added;
      for (int v : layer)
        mesh.for_each_outgoing(v, [&](int h) {
          const int w = mesh.to_vertex(h);
          if (stamp[static_cast<std::size_t>(w)] == round) return;
          stamp[static_cast<std::size_t>(w)] = round;
          added.push_back(w);
          if (moving_either(w) && !in_block[static_cast<std::size_t>(w)]) in_block[static_cast<std::size_t>(w)] = 1, next.push_back(w);
        });
      layer = std::move(added);
    }
    frontier = std::move(next);
  }
  // Their unknowns, before and now (the moving vertices grown by `rings`), back to the reference;
  // the changed rows too (a row outside every block is the reference); then the blocks re-solved.
  std::vector<char> reset(static_cast<std::size_t>(n), 0);
  std::vector<int> rewritten;
  std::vector<int> layer = block;
  for (int v : block) reset[static_cast<std::size_t>(v)] = 1;
  rewritten = block;
  for (int ring = 0; ring < rings; ++ring) layer = grow_ring(mesh, layer, reset, rewritten);
  for (int v : changed)
    if (!reset[static_cast<std::size_t>(v)]) reset[static_cast<std::size_t>(v)] = 1, rewritten.push_back(v);
  for (int v : rewritten) X.row(v) = reference.row(v);
  std::vector<int> moving;
  for (int v : block)
    if (moving_now(v)) moving.push_back(v);
  std::sort(moving.begin(), moving.end());
  (void)fit_block(mesh, limit_by_rows, limit_displacement, moving, rings, X);
  return rewritten;
}

}  // namespace fairshape::feature
