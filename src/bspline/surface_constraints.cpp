#include "fairshape/bspline/surface_constraints.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "fairshape/bspline/uniform_basis.h"
#include "fairshape/core/error.h"
#include "fairshape/problem/constrained_system.h"

namespace fairshape::bspline {

void check_in_domain(const HierarchicalSurface& s, double u, double v, const std::string& what) {
  if (s.in_domain(u, v)) return;
  std::ostringstream m;
  m << what << ": (u, v) = (" << u << ", " << v << ") is outside the parameter domain ";
  if (s.shape().periodic_u) m << "(periodic in u) x [0, " << s.shape().spans_v << "]";
  else m << "[0, " << s.shape().spans_u << "] x [0, " << s.shape().spans_v << "]";
  throw InvalidInput(m.str());
}

namespace {
ConstraintRows single_row(const HierarchicalSurface& s, const BasisRow& row, double BasisEntry::*field, const Vec3& target) {
  ConstraintRows out;
  Triplets t;
  for (const BasisEntry& e : row) t.emplace_back(0, e.dof, e.*field);
  out.A.resize(1, s.dof_count());
  out.A.setFromTriplets(t.begin(), t.end());
  out.C = target.transpose();
  return out;
}
}  // namespace

ConstraintRows point_rows(const HierarchicalSurface& s, double u, double v, const Vec3& target) {
  check_in_domain(s, u, v, "point constraint");
  if (!target.allFinite()) throw InvalidInput("point constraint: target is not finite");
  BasisRow row;
  s.basis(u, v, row);
  return single_row(s, row, &BasisEntry::value, target);
}

ConstraintRows offset_rows(const HierarchicalSurface& s, const Eigen::Vector2d& at, const Eigen::Vector2d& from, const Vec3& offset) {
  check_in_domain(s, at.x(), at.y(), "offset constraint");
  check_in_domain(s, from.x(), from.y(), "offset constraint, from");
  if (!offset.allFinite()) throw InvalidInput("offset constraint: the offset is not finite");
  if (at == from) throw InvalidInput("offset constraint: the point and the point it is offset from are the same");
  BasisRow a, b;
  s.basis(at.x(), at.y(), a);
  s.basis(from.x(), from.y(), b);
  Triplets t;  // duplicates (functions reaching both points) are summed by setFromTriplets
  for (const BasisEntry& e : a) t.emplace_back(0, e.dof, e.value);
  for (const BasisEntry& e : b) t.emplace_back(0, e.dof, -e.value);
  ConstraintRows out;
  out.A.resize(1, s.dof_count());
  out.A.setFromTriplets(t.begin(), t.end());
  out.A.prune(0.0);
  out.C = offset.transpose();
  return out;
}

ConstraintRows tangent_rows(const HierarchicalSurface& s, double u, double v, int direction, const Vec3& target) {
  check_in_domain(s, u, v, "tangent constraint");
  FAIRSHAPE_ASSERT(direction == 0 || direction == 1, "tangent direction must be 0 (u) or 1 (v)");
  if (!target.allFinite()) throw InvalidInput("tangent constraint: target is not finite");
  BasisRow row;
  s.basis(u, v, row);
  // A derivative in design units: D_x = D_u / h_u (SheetShape::span_size).
  ConstraintRows out = single_row(s, row, direction == 0 ? &BasisEntry::du : &BasisEntry::dv, target);
  out.A /= s.shape().span_size[direction];
  return out;
}

CoupledRows normal_rows(const HierarchicalSurface& s, double u, double v, const Vec3& normal) {
  check_in_domain(s, u, v, "normal constraint");
  if (!normal.allFinite() || normal.norm() == 0) throw InvalidInput("normal constraint: the normal must be a nonzero finite vector");
  const Vec3 n = normal.normalized();
  BasisRow row;
  s.basis(u, v, row);
  const int dofs = s.dof_count();
  Triplets t;
  for (const BasisEntry& e : row)
    for (int c = 0; c < 3; ++c) {
      if (n[c] == 0) continue;
      t.emplace_back(0, c * dofs + e.dof, n[c] * e.du / s.shape().span_size.x());
      t.emplace_back(1, c * dofs + e.dof, n[c] * e.dv / s.shape().span_size.y());
    }
  CoupledRows out;
  out.A.resize(2, 3 * dofs);
  out.A.setFromTriplets(t.begin(), t.end());
  out.b = Eigen::VectorXd::Zero(2);
  return out;
}

CoupledRows stacked(const ConstraintRows& rows) {
  CoupledRows out;
  out.A = block_diagonal(rows.A, 3);
  out.b = Eigen::Map<const Eigen::VectorXd>(rows.C.data(), rows.C.size());  // column-major: [C_x; C_y; C_z]
  return out;
}

template <class Point>
Point polyline_at(const std::vector<Point>& pts, double t) {
  const double x = std::clamp(t, 0.0, 1.0) * static_cast<double>(pts.size() - 1);
  const std::size_t k = std::min(static_cast<std::size_t>(x), pts.size() - 2);
  const double a = x - static_cast<double>(k);
  return ((1 - a) * pts[k] + a * pts[k + 1]).eval();
}
template Eigen::Vector2d polyline_at(const std::vector<Eigen::Vector2d>&, double);
template Vec3 polyline_at(const std::vector<Vec3>&, double);

Vec3 curve_target_at(const CurveAttachment& curve, double t) {
  if (!curve.traced) return polyline_at(curve.space, t);
  // The edits' offset is the polyline of space − traced through the samples around t.
  const std::size_t n = curve.space.size();
  const double x = std::clamp(t, 0.0, 1.0) * static_cast<double>(n - 1);
  const std::size_t k = std::min(static_cast<std::size_t>(x), n - 2);
  const double a = x - static_cast<double>(k);
  const auto traced_at = [&](double tt) {
    const Eigen::Vector2d c = polyline_at(curve.uv, tt);
    return Vec3(curve.traced->surface.position(curve.traced->P, c.x(), c.y()));
  };
  const double t0 = static_cast<double>(k) / static_cast<double>(n - 1), t1 = static_cast<double>(k + 1) / static_cast<double>(n - 1);
  const Vec3 offset = (1 - a) * (curve.space[k] - traced_at(t0)) + a * (curve.space[k + 1] - traced_at(t1));
  return traced_at(t) + offset;
}

void check_curve_attachment(const HierarchicalSurface& s, const CurveAttachment& curve) {
  if (curve.uv.size() < 2 || curve.space.size() < 2)
    throw InvalidInput("curve constraint: needs at least two (u, v) points and two space points");
  for (std::size_t k = 0; k < curve.uv.size(); ++k)
    check_in_domain(s, curve.uv[k].x(), curve.uv[k].y(), "curve constraint, (u, v) point " + std::to_string(k));
  for (const Vec3& x : curve.space)
    if (!x.allFinite()) throw InvalidInput("curve constraint: a space-curve point is not finite");
}

ConstraintRows curve_rows(const HierarchicalSurface& s, const CurveAttachment& curve, CurveQuadrature quadrature) {
  check_curve_attachment(s, curve);
  const int r = s.degree();
  const GaussRule g = gauss_legendre(quadrature == CurveQuadrature::Exact ? r + 1 : (r + 2) / 2);
  const double grid = std::ldexp(1.0, s.level_count() - 1);  // leaf cells end on the finest grid lines

  // Breakpoints in t: polyline vertices of both curves, and every finest grid line crossed.
  std::vector<double> ts;
  const double nuv = static_cast<double>(curve.uv.size() - 1), nsp = static_cast<double>(curve.space.size() - 1);
  for (std::size_t k = 0; k <= curve.uv.size() - 1; ++k) ts.push_back(k / nuv);
  for (std::size_t k = 0; k <= curve.space.size() - 1; ++k) ts.push_back(k / nsp);
  for (std::size_t k = 0; k + 1 < curve.uv.size(); ++k)
    for (int axis = 0; axis < 2; ++axis) {
      const double a = curve.uv[k][axis] * grid, b = curve.uv[k + 1][axis] * grid;
      for (double line = std::ceil(std::min(a, b)); line < std::max(a, b); line += 1)
        ts.push_back((k + (line - a) / (b - a)) / nuv);
    }
  std::sort(ts.begin(), ts.end());

  Triplets t;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(s.dof_count(), 3);
  BasisRow row;
  for (std::size_t k = 0; k + 1 < ts.size(); ++k) {
    const double t0 = ts[k], t1 = ts[k + 1];
    if (t1 - t0 < 1e-14) continue;
    const double ds = (polyline_at(curve.uv, t1) - polyline_at(curve.uv, t0)).norm();  // uv is linear here
    for (std::size_t q = 0; q < g.nodes.size(); ++q) {
      const double tq = t0 + g.nodes[q] * (t1 - t0), w = g.weights[q] * ds;
      const Eigen::Vector2d c = polyline_at(curve.uv, tq);
      const Vec3 D = polyline_at(curve.space, tq);
      s.basis(c.x(), c.y(), row);
      for (const BasisEntry& a : row) {
        rhs.row(a.dof) += w * a.value * D.transpose();
        for (const BasisEntry& b : row) t.emplace_back(a.dof, b.dof, w * a.value * b.value);
      }
    }
  }
  SparseMatrix M(s.dof_count(), s.dof_count());
  M.setFromTriplets(t.begin(), t.end());
  // One row per control point the curve reaches.
  std::vector<int> reached;
  for (int k = 0; k < M.outerSize(); ++k)
    if (M.col(k).nonZeros() > 0) reached.push_back(k);  // M is symmetric: column k ↔ row k
  ConstraintRows out;
  Triplets rows;
  out.C.resize(static_cast<Eigen::Index>(reached.size()), 3);
  for (std::size_t i = 0; i < reached.size(); ++i) {
    for (SparseMatrix::InnerIterator it(M, reached[i]); it; ++it)
      rows.emplace_back(static_cast<int>(i), static_cast<int>(it.row()), it.value());
    out.C.row(static_cast<Eigen::Index>(i)) = rhs.row(reached[i]);
  }
  out.A.resize(static_cast<Eigen::Index>(reached.size()), s.dof_count());
  out.A.setFromTriplets(rows.begin(), rows.end());
  if (reached.empty()) throw InvalidInput("curve constraint: the (u, v) curve has zero length");
  return out;
}

std::vector<Vec3> surface_curve(const HierarchicalSurface& s, const Eigen::MatrixXd& P,
                                const std::vector<Eigen::Vector2d>& uv, int samples) {
  FAIRSHAPE_ASSERT(samples >= 2 && uv.size() >= 2, "surface_curve needs two samples and two uv points");
  std::vector<Vec3> out;
  for (int k = 0; k < samples; ++k) {
    const Eigen::Vector2d c = polyline_at(uv, static_cast<double>(k) / (samples - 1));
    check_in_domain(s, c.x(), c.y(), "surface curve");
    out.push_back(s.position(P, c.x(), c.y()));
  }
  return out;
}

ConstraintRows stack(const std::vector<ConstraintRows>& parts, int dofs) {
  ConstraintRows out;
  if (parts.empty()) {
    out.A.resize(0, dofs);
    out.C.resize(0, 3);
    return out;
  }
  std::vector<const SparseMatrix*> blocks;
  Eigen::Index m = 0;
  for (const auto& p : parts) blocks.push_back(&p.A), m += p.A.rows();
  out.A = stack_rows(blocks);
  out.C.resize(m, 3);
  Eigen::Index offset = 0;
  for (const auto& p : parts) {
    out.C.middleRows(offset, p.A.rows()) = p.C;
    offset += p.A.rows();
  }
  return out;
}

}  // namespace fairshape::bspline
