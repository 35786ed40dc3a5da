#include "fairshape/design/multires_constraints.h"

#include <map>
#include <sstream>

#include <array>
#include <cmath>

#include <Eigen/Geometry>

#include "fairshape/constraint/crease_normals.h"
#include "fairshape/mesh/orientation.h"
#include "fairshape/energy/divided_differences.h"
#include "fairshape/subdivision/limit.h"

namespace fairshape {

namespace {

void check_edit_level(const MultiresSurface& h, int l) {
  if (l < 0 || l > h.levels())
    throw InvalidInput("edit level " + std::to_string(l) + " outside the hierarchy [0, " + std::to_string(h.levels()) + "]");
}

void check_place(const MultiresSurface& h, int l, int level, int vertex, const std::string& label) {
  if (level < l || level > h.levels())
    throw InvalidInput(label + ": level " + std::to_string(level) + " is " +
                       (level < l ? "coarser than the edit level " + std::to_string(l) +
                                        ": rows propagate only to coarser levels, so give it influence_level: k with "
                                        "k <= " + std::to_string(level) +
                                        " (its own region on level k, Boier-Martin et al. 4.2) or place it on a level >= " +
                                        std::to_string(l)
                                  : "not in the hierarchy (levels 0.." + std::to_string(h.levels()) + ")"));
  if (vertex < 0 || vertex >= h.mesh(level).n_vertices())
    throw InvalidInput(label + ": vertex " + std::to_string(vertex) + " does not exist on level " +
                       std::to_string(level) + " (" + std::to_string(h.mesh(level).n_vertices()) + " vertices)");
}

// A constraint at a point of level k's limit surface (constraint.h SurfacePoint): its stencils
// must be weights over level k's vertices.
void check_surface_point(const MultiresSurface& h, int level, const SurfacePoint& sp, const std::string& label) {
  const int n = h.mesh(level).n_vertices();
  for (const Stencil* s : {&sp.position, &sp.du, &sp.dv})
    for (const auto& [vertex, w] : *s)
      if (vertex < 0 || vertex >= n || !std::isfinite(w))
        throw InvalidInput(label + ": the surface point's stencil names vertex " + std::to_string(vertex) +
                           " (level " + std::to_string(level) + " has " + std::to_string(n) +
                           " vertices) or a non-finite weight");
}

// The row of a surface point on the edit level: its stencil w over level k times P_{l→k}
// (rows = level-k vertices), Σ_j w_j e_jᵀ P_{l→k} — Table 1's propagation applied to a
// combination of vertices instead of one.
void add_stencil_row(const RowSparseMatrix& P, const Stencil& stencil, int row, Triplets& t) {
  for (const auto& [vertex, w] : stencil)
    for (RowSparseMatrix::InnerIterator it(P, vertex); it; ++it) t.emplace_back(row, static_cast<int>(it.col()), w * it.value());
}

// The derivative stencils ∂S/∂u, ∂S/∂v of a surface point as the two sparse rows a normal
// constraint makes perpendicular to N (in place of the divided differences at a vertex).
std::array<Eigen::SparseVector<double>, 2> derivative_rows(const SurfaceMesh& mesh, const SurfacePoint& sp) {
  std::array<Eigen::SparseVector<double>, 2> rows;
  for (int r = 0; r < 2; ++r) {
    rows[r].resize(mesh.n_vertices());
    for (const auto& [vertex, w] : r == 0 ? sp.du : sp.dv) rows[r].coeffRef(vertex) += w;
  }
  return rows;
}

// Rows u and v of one normal constraint, over level k's vertices: the tangents Q_u, Q_v of
// the local fit are linear in the positions, a_r · P with a_r(j) = D_{r,j}, a_r(i) = −Σ_j D_{r,j}.
std::array<Eigen::SparseVector<double>, 2> tangent_rows(const SurfaceMesh& mesh, int vertex) {
  const LocalFit fit = local_fit(mesh, vertex);
  std::array<Eigen::SparseVector<double>, 2> rows;
  for (int r = 0; r < 2; ++r) {
    rows[r].resize(mesh.n_vertices());
    for (std::size_t j = 0; j < fit.ring.size(); ++j)
      rows[r].coeffRef(fit.ring[j]) += fit.D(r, static_cast<Eigen::Index>(j));
    rows[r].coeffRef(vertex) -= fit.D.row(r).sum();
  }
  return rows;
}

// a · P: the tangent that row a measures on positions P.
Vec3 tangent_at(const Eigen::SparseVector<double>& a, const MatrixX3& P) {
  Vec3 q = Vec3::Zero();
  for (Eigen::SparseVector<double>::InnerIterator e(a); e; ++e) q += e.value() * P.row(e.index()).transpose();
  return q;
}

// The rows of normal constraint `nc` on its level's vertices: the tangents of the vertex's
// local fit, or ∂S/∂u, ∂S/∂v at a surface point.
std::array<Eigen::SparseVector<double>, 2> rows_of(const SurfaceMesh& mesh, const NormalConstraint& nc) {
  return nc.surface.empty() ? tangent_rows(mesh, nc.vertex) : derivative_rows(mesh, nc.surface);
}

// a · P · N: the component along N of the tangent that row a measures on the positions P of `now`.
double along(const Eigen::SparseVector<double>& a, const SurfaceMesh& now, const Vec3& N) {
  double d = 0;
  for (Eigen::SparseVector<double>::InnerIterator e(a); e; ++e) d += e.value() * now.position(static_cast<int>(e.index())).dot(N);
  return d;
}

// The normal constraints after the checks (level, vertex, a nonzero finite normal), each
// requested normal once. Two normals on one vertex must agree: the rows of N and of −N are the
// same equations (the tangent plane ⊥ N), so opposite normals would be "satisfied" by either
// orientation.
std::vector<const NormalConstraint*> distinct_normals(const MultiresSurface& h, int l,
                                                      const std::vector<NormalConstraint>& normals) {
  std::map<std::pair<int, int>, const NormalConstraint*> seen;
  std::vector<const NormalConstraint*> unique;
  for (const auto& nc : normals) {
    check_place(h, l, nc.level, nc.vertex, nc.label);
    if (!nc.normal.allFinite() || nc.normal.norm() == 0) throw InvalidInput(nc.label + ": the normal is zero or not finite");
    if (!nc.surface.empty()) {  // a surface point: its own rows, never merged with a vertex's
      check_surface_point(h, nc.level, nc.surface, nc.label);
      unique.push_back(&nc);
      continue;
    }
    refuse_normal_on_crease(h.mesh(nc.level), h.options(), nc.level, nc.vertex, nc.level < h.levels(), nc.label);
    auto [first, inserted] = seen.try_emplace({nc.level, nc.vertex}, &nc);
    if (inserted) {
      unique.push_back(&nc);
    } else if ((first->second->normal.normalized() - nc.normal.normalized()).norm() > 1e-12) {
      std::ostringstream os;
      os << "vertex " << nc.vertex << " of level " << nc.level << " has incompatible normals: " << first->second->label
         << " asks for [" << first->second->normal.transpose() << "], " << nc.label << " for [" << nc.normal.transpose()
         << "]";
      throw InvalidInput(os.str());
    }
  }
  return unique;
}

// The point constraints after the checks (level, vertex, a finite target), each target once:
// incompatible targets on one vertex are an error, a repeated identical one is harmless.
// `row_of` (optional): each constraint's row, index for index with `cs`.
std::vector<const PointConstraint*> distinct_points(const MultiresSurface& h, int l, const std::vector<PointConstraint>& cs,
                                                    std::vector<int>* row_of = nullptr) {
  std::map<std::tuple<int, int, bool>, std::pair<const PointConstraint*, int>> seen;
  std::vector<const PointConstraint*> unique;
  for (const auto& c : cs) {
    check_place(h, l, c.level, c.vertex, c.label);
    if (!c.offset.allFinite()) throw InvalidInput(c.label + ": target is not finite");
    if (!c.surface.empty()) {  // a surface point: its own row, never merged with a vertex's
      check_surface_point(h, c.level, c.surface, c.label);
      if (row_of) row_of->push_back(static_cast<int>(unique.size()));
      unique.push_back(&c);
      continue;
    }
    auto [found, inserted] = seen.try_emplace({c.level, c.vertex, c.on_limit}, &c, static_cast<int>(unique.size()));
    if (row_of) row_of->push_back(found->second.second);
    const auto* it = &found->second;  // it->first: the constraint that made the row
    if (inserted) unique.push_back(&c);
    else if ((it->first->offset - c.offset).norm() > 1e-12 * (1.0 + c.offset.norm())) {
      std::ostringstream os;
      os << "vertex " << c.vertex << " of level " << c.level << " has incompatible targets: " << it->first->label
         << " asks for [" << it->first->offset.transpose() << "], " << c.label << " for [" << c.offset.transpose() << "]";
      throw InvalidInput(os.str());
    }
  }
  return unique;
}

// How far the point a constraint names (a vertex of its level, that vertex's limit point, or a
// point of the limit surface)
// has moved from `h` to `current`. Catmull-Clark and Loop limit stencils depend on the
// connectivity alone, so one limit matrix per level serves both shapes.
Vec3 moved_so_far(const MultiresSurface& h, const MultiresSurface& current, const PointConstraint& c,
                  std::map<int, RowSparseMatrix>& limit_rows) {
  const MatrixX3& now = current.mesh(c.level).positions();
  const MatrixX3& rest = h.mesh(c.level).positions();
  if (!c.surface.empty()) {  // a point of the limit surface: its stencil over the level's vertices
    Vec3 moved = Vec3::Zero();
    for (const auto& [v, w] : c.surface.position) moved += w * (now.row(v) - rest.row(v)).transpose();
    return moved;
  }
  if (!c.on_limit) return (now.row(c.vertex) - rest.row(c.vertex)).transpose();
  auto it = limit_rows.find(c.level);
  if (it == limit_rows.end())
    it = limit_rows.emplace(c.level, RowSparseMatrix(limit_matrix(h.mesh(c.level), h.options()))).first;
  Vec3 moved = Vec3::Zero();
  for (RowSparseMatrix::InnerIterator e(it->second, c.vertex); e; ++e)
    moved += e.value() * (now.row(e.col()) - rest.row(e.col())).transpose();
  return moved;
}

void require_fixed_position(bool any_point_row, bool any_normal) {
  if (!any_point_row)
    throw InvalidInput(any_normal ? "edit: normal constraints fix no position: add a point or fixed constraint"
                                  : "edit: no constraint: the deformation is undetermined (add a point or fixed constraint)");
}

void add_normal_rows(const MultiresSurface& h, int l, const std::vector<NormalConstraint>& normals,
                     const MultiresSurface* current, LinearConstraints& out) {
  const int n = h.mesh(l).n_vertices();
  std::map<int, RowSparseMatrix> prolongation_to;  // level k → P_{l→k}, rows = level-k vertices
  Triplets t;
  std::vector<double> c;
  for (const NormalConstraint* requested : distinct_normals(h, l, normals)) {
    const NormalConstraint& nc = *requested;
    if (nc.rows == NormalRows::Frame) continue;  // rows of the point kind (add_frame_rows)
    const Vec3 N = nc.normal.normalized();
    auto it = prolongation_to.find(nc.level);
    if (it == prolongation_to.end()) it = prolongation_to.emplace(nc.level, RowSparseMatrix(h.prolongation(l, nc.level))).first;
    const SurfaceMesh& mesh = h.mesh(nc.level);
    for (const auto& a : rows_of(mesh, nc)) {
      // a · ΔP^k = (a P_{l→k}) · ΔP^l: the row on the edit level, times N on each coordinate block.
      Eigen::SparseVector<double> row(n);
      for (Eigen::SparseVector<double>::InnerIterator e(a); e; ++e)
        row += e.value() * Eigen::SparseVector<double>(it->second.row(e.index()).transpose());
      const int r = static_cast<int>(c.size());
      for (Eigen::SparseVector<double>::InnerIterator e(row); e; ++e)
        for (int d = 0; d < 3; ++d)
          if (N[d] != 0) t.emplace_back(r, d * n + static_cast<int>(e.index()), e.value() * N[d]);
      c.push_back(-along(a, current ? current->mesh(nc.level) : mesh, N));
    }
  }
  out.A_coupled.resize(static_cast<Eigen::Index>(c.size()), 3 * n);
  out.A_coupled.setFromTriplets(t.begin(), t.end());
  out.C_coupled = Eigen::Map<const Eigen::VectorXd>(c.data(), static_cast<Eigen::Index>(c.size()));
}

// What frame rows ask of normal constraint `nc`'s tangents: the rest ones (of `h`) turned by the
// shortest rotation of the rest normal — oriented like the faces, as achieved_normal reports it —
// onto N. Minus where they are on `now`: the deformation still missing.
std::array<Vec3, 2> frame_targets(const SurfaceMesh& rest, const SurfaceMesh& now, const NormalConstraint& nc) {
  const Vec3 rest_normal = achieved_normal(rest, rest.positions(), nc);
  const Eigen::Matrix3d R = Eigen::Quaterniond::FromTwoVectors(rest_normal, nc.normal.normalized()).toRotationMatrix();
  const auto rows = rows_of(rest, nc);
  std::array<Vec3, 2> missing;
  for (int r = 0; r < 2; ++r) missing[r] = R * tangent_at(rows[r], rest.positions()) - tangent_at(rows[r], now.positions());
  return missing;
}

// The frame rows of the normal constraints with rows: frame, appended to the point rows (papers/
// boier-martin/README.md, "Folds and reversed normals"): each tangent row a of level k is a row of
// the point kind on the edit level, (a P_{l→k}) ΔP^l = R Q⁰ − Q — one row, three target columns —
// so N is met with its own orientation (Q_u × Q_v = R (Q_u⁰ × Q_v⁰)).
void add_frame_rows(const MultiresSurface& h, int l, const std::vector<NormalConstraint>& normals,
                    const MultiresSurface* current, LinearConstraints& out) {
  std::vector<const NormalConstraint*> framed;
  for (const NormalConstraint* nc : distinct_normals(h, l, normals))
    if (nc->rows == NormalRows::Frame) framed.push_back(nc);
  if (framed.empty()) return;
  const int n = h.mesh(l).n_vertices();
  const Eigen::Index first = out.A.rows();
  Triplets t;
  for (int k = 0; k < out.A.outerSize(); ++k)
    for (SparseMatrix::InnerIterator e(out.A, k); e; ++e) t.emplace_back(static_cast<int>(e.row()), static_cast<int>(e.col()), e.value());
  out.C.conservativeResize(first + 2 * static_cast<Eigen::Index>(framed.size()), 3);
  std::map<int, RowSparseMatrix> prolongation_to;
  Eigen::Index r = first;
  for (const NormalConstraint* nc : framed) {
    auto it = prolongation_to.find(nc->level);
    if (it == prolongation_to.end()) it = prolongation_to.emplace(nc->level, RowSparseMatrix(h.prolongation(l, nc->level))).first;
    const SurfaceMesh& rest = h.mesh(nc->level);
    const std::array<Vec3, 2> missing = frame_targets(rest, current ? current->mesh(nc->level) : rest, *nc);
    const auto rows = rows_of(rest, *nc);
    for (int q = 0; q < 2; ++q, ++r) {
      for (Eigen::SparseVector<double>::InnerIterator e(rows[q]); e; ++e)
        for (RowSparseMatrix::InnerIterator p(it->second, e.index()); p; ++p)
          t.emplace_back(static_cast<int>(r), static_cast<int>(p.col()), e.value() * p.value());
      out.C.row(r) = missing[q].transpose();
    }
  }
  out.A.resize(r, n);
  out.A.setFromTriplets(t.begin(), t.end());
}

}  // namespace

LinearConstraints propagate_constraints(const MultiresSurface& h, int l, const DesignConstraints& dc,
                                        const MultiresSurface* current) {
  LinearConstraints out = propagate_constraints(h, l, dc.points, current);
  if (!dc.normals.empty()) {
    add_frame_rows(h, l, dc.normals, current, out);
    add_normal_rows(h, l, dc.normals, current, out);
  }
  return out;
}

LinearConstraints missing_targets(const MultiresSurface& h, const DesignConstraints& dc, const MultiresSurface& current) {
  const std::vector<const PointConstraint*> points = distinct_points(h, 0, dc.points);
  std::map<int, RowSparseMatrix> limit_rows;
  LinearConstraints out;
  out.C.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t r = 0; r < points.size(); ++r)
    out.C.row(static_cast<Eigen::Index>(r)) = (points[r]->offset - moved_so_far(h, current, *points[r], limit_rows)).transpose();
  std::vector<double> c;
  const std::vector<const NormalConstraint*> normals = distinct_normals(h, 0, dc.normals);
  for (const NormalConstraint* nc : normals) {  // in add_frame_rows' order
    if (nc->rows != NormalRows::Frame) continue;
    const std::array<Vec3, 2> missing = frame_targets(h.mesh(nc->level), current.mesh(nc->level), *nc);
    out.C.conservativeResize(out.C.rows() + 2, 3);
    for (int q = 0; q < 2; ++q) out.C.row(out.C.rows() - 2 + q) = missing[q].transpose();
  }
  for (const NormalConstraint* nc : normals) {
    if (nc->rows == NormalRows::Frame) continue;
    const Vec3 N = nc->normal.normalized();
    const SurfaceMesh& now = current.mesh(nc->level);
    for (const auto& a : rows_of(h.mesh(nc->level), *nc)) c.push_back(-along(a, now, N));
  }
  out.C_coupled = Eigen::Map<const Eigen::VectorXd>(c.data(), static_cast<Eigen::Index>(c.size()));
  return out;
}

std::vector<int> point_rows(const MultiresSurface& h, int edit_level, const std::vector<PointConstraint>& points) {
  std::vector<int> rows;
  (void)distinct_points(h, edit_level, points, &rows);
  return rows;
}

void require_fixed_position(const LinearConstraints& lc) { require_fixed_position(lc.A.rows() > 0, lc.coupled()); }

void check_constraints(const MultiresSurface& h, int l, const DesignConstraints& dc) {
  check_edit_level(h, l);
  const bool any_point = !distinct_points(h, l, dc.points).empty();
  const bool any_normal = !distinct_normals(h, l, dc.normals).empty();
  require_fixed_position(any_point, any_normal);
}

Vec3 estimated_normal(const SurfaceMesh& D_mesh, const MatrixX3& positions, int vertex) {
  const auto rows = tangent_rows(D_mesh, vertex);
  return tangent_at(rows[0], positions).cross(tangent_at(rows[1], positions)).normalized();
}

Vec3 achieved_normal(const SurfaceMesh& mesh, const MatrixX3& positions, const NormalConstraint& nc) {
  const auto rows = rows_of(mesh, nc);
  const auto cross_at = [&rows](const MatrixX3& P) { return Vec3(tangent_at(rows[0], P).cross(tangent_at(rows[1], P))); };
  // The tangents' order is the local fit's, not the faces': orient by the rest surface.
  const Vec3 faces = nc.surface.empty() ? area_normal(mesh, mesh.positions(), nc.vertex)
                                        : vector_area(mesh, mesh.positions(), nc.surface.at.face);
  const double sign = cross_at(mesh.positions()).dot(faces) < 0 ? -1.0 : 1.0;
  const Vec3 n = sign * cross_at(positions);
  return n.norm() > 0 ? Vec3(n.normalized()) : Vec3::Zero();
}

LinearConstraints propagate_constraints(const MultiresSurface& h, int l, const std::vector<PointConstraint>& cs,
                                        const MultiresSurface* current) {
  check_edit_level(h, l);
  const std::vector<const PointConstraint*> unique = distinct_points(h, l, cs);
  // One composed operator per level that has constraints.
  std::map<std::pair<int, bool>, RowSparseMatrix> rows_of;
  for (const auto* c : unique) {
    auto key = std::make_pair(c->level, c->on_limit);
    if (rows_of.count(key)) continue;
    SparseMatrix P = h.prolongation(l, c->level);
    if (c->on_limit) P = SparseMatrix(limit_matrix(h.mesh(c->level), h.options()) * P);
    rows_of.emplace(key, RowSparseMatrix(P));
  }
  std::map<int, RowSparseMatrix> limit_rows;  // per level, for moved_so_far
  LinearConstraints out;
  out.C.resize(static_cast<Eigen::Index>(unique.size()), 3);
  Triplets t;
  for (std::size_t r = 0; r < unique.size(); ++r) {
    const RowSparseMatrix& P = rows_of.at({unique[r]->level, unique[r]->on_limit});
    if (!unique[r]->surface.empty()) add_stencil_row(P, unique[r]->surface.position, static_cast<int>(r), t);
    else
      for (RowSparseMatrix::InnerIterator it(P, unique[r]->vertex); it; ++it)
        t.emplace_back(static_cast<int>(r), static_cast<int>(it.col()), it.value());
    out.C.row(static_cast<Eigen::Index>(r)) = unique[r]->offset.transpose();
    if (current) out.C.row(static_cast<Eigen::Index>(r)) -= moved_so_far(h, *current, *unique[r], limit_rows).transpose();
  }
  out.A.resize(static_cast<Eigen::Index>(unique.size()), h.mesh(l).n_vertices());
  out.A.setFromTriplets(t.begin(), t.end());
  return out;
}

}  // namespace fairshape
