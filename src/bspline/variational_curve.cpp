#include "fairshape/bspline/variational_curve.h"

#include <algorithm>
#include <cmath>

#include <Eigen/SparseCholesky>

#include "fairshape/bspline/uniform_basis.h"
#include "fairshape/core/error.h"

namespace fairshape::bspline {

void validate(const CurveEnergy& e) {
  if (!std::isfinite(e.alpha) || !std::isfinite(e.beta) || e.alpha < 0 || e.beta < 0)
    throw InvalidInput("variational curve: alpha and beta must be finite and >= 0");
  if (e.alpha == 0 && e.beta == 0) throw InvalidInput("variational curve: alpha and beta are both 0 (no energy to minimize)");
}

namespace {

double polyline_length(const std::vector<Vec3>& pts) {
  double L = 0;
  for (std::size_t k = 0; k + 1 < pts.size(); ++k) L += (pts[k + 1] - pts[k]).norm();
  return L;
}

// The polyline with every segment cut into `pieces` equal ones: the same path, the same t.
std::vector<Vec3> subdivided(const std::vector<Vec3>& pts, int pieces) {
  std::vector<Vec3> out{pts.front()};
  for (std::size_t k = 0; k + 1 < pts.size(); ++k)
    for (int i = 1; i <= pieces; ++i) out.push_back(pts[k] + (pts[k + 1] - pts[k]) * (static_cast<double>(i) / pieces));
  return out;
}

// N (points × knot functions): the knot basis at each t.
SparseMatrix knot_values(const ClampedKnotBasis& basis, const std::vector<double>& t) {
  Triplets trip;
  std::vector<double> values;
  int first = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    basis.evaluate(t[k], first, values);
    for (std::size_t i = 0; i < values.size(); ++i) trip.emplace_back(static_cast<int>(k), first + static_cast<int>(i), values[i]);
  }
  SparseMatrix N(static_cast<Eigen::Index>(t.size()), basis.size());
  N.setFromTriplets(trip.begin(), trip.end());
  return N;
}

// The unknowns q minimizing Σ_k |X(t_k) − P_k|² with X = N R q.
Eigen::MatrixXd least_squares_fit(const HierarchicalCurveBasis& basis, const std::vector<double>& t, const Eigen::MatrixXd& P) {
  const SparseMatrix NR = knot_values(basis.knot_basis(), t) * basis.to_knot_basis();
  const SparseMatrix normal = NR.transpose() * NR;
  const Eigen::SimplicialLDLT<SparseMatrix> ldlt(normal);
  if (ldlt.info() != Eigen::Success) throw InvalidInput("variational curve: the least-squares fit of the polyline is singular");
  Eigen::MatrixXd q = ldlt.solve(Eigen::MatrixXd(NR.transpose() * P));
  if (!q.allFinite()) throw InvalidInput("variational curve: the least-squares fit of the polyline is singular");
  return q;
}

}  // namespace

VariationalCurve::VariationalCurve(const CurveShape& shape, const std::vector<Vec3>& polyline)
    : shape_(shape), basis_(shape.spans, shape.degree) {
  if (polyline.size() < 2) throw InvalidInput("variational curve: its initial polyline needs at least two points");
  for (const Vec3& x : polyline)
    if (!x.allFinite()) throw InvalidInput("variational curve: a point of its initial polyline is not finite");
  length_ = polyline_length(polyline);
  if (!(length_ > 0)) throw InvalidInput("variational curve: its initial polyline has zero length");
  // n or more samples equally spaced in t leave every basis function one of its own inside its
  // support (Schoenberg-Whitney holds on clamped uniform knots), so the fit is determined.
  const int needed = dof_count();
  const int segments = static_cast<int>(polyline.size()) - 1;
  const int pieces = static_cast<int>(polyline.size()) >= needed ? 1 : (needed - 1 + segments - 1) / segments;
  const std::vector<Vec3> points = pieces == 1 ? polyline : subdivided(polyline, pieces);
  std::vector<double> t;
  Eigen::MatrixXd P(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t k = 0; k < points.size(); ++k) {
    t.push_back(static_cast<double>(k) / static_cast<double>(points.size() - 1));
    P.row(static_cast<Eigen::Index>(k)) = points[k].transpose();
  }
  set_control_points(least_squares_fit(basis_, t, P));
}

VariationalCurve::VariationalCurve(const CurveShape& shape, Eigen::MatrixXd control_points, double design_length)
    : shape_(shape), basis_(shape.spans, shape.degree), length_(design_length) {
  if (!(design_length > 0) || !std::isfinite(design_length)) throw InvalidInput("variational curve: design length must be positive");
  set_control_points(std::move(control_points));
}

void VariationalCurve::set_control_points(Eigen::MatrixXd q) {
  if (q.rows() != dof_count() || q.cols() != 3)
    throw InvalidInput("variational curve: expected " + std::to_string(dof_count()) + " x 3 control points");
  q_ = std::move(q);
  x_ = basis_.to_knot_basis() * q_;
}

int VariationalCurve::refine(const std::vector<CurveSpan>& cells) {
  HierarchicalCurveBasis finer = basis_;
  const int added = finer.refine(cells);
  // r + 1 points in every new leaf determine the fit (Schoenberg–Whitney on each leaf), and
  // the old X lies in the finer space, so the fit reproduces it.
  const GaussRule g = gauss_legendre(basis_.degree() + 1);
  std::vector<double> t;
  for (const CurveSpan& leaf : finer.leaf_cells())
    for (double node : g.nodes) t.push_back(leaf.t0 + node * (leaf.t1 - leaf.t0));
  const Eigen::MatrixXd X = knot_values(knot_basis(), t) * x_;
  Eigen::MatrixXd q = least_squares_fit(finer, t, X);
  basis_ = std::move(finer);
  set_control_points(std::move(q));
  return added;
}

Vec3 VariationalCurve::position(double t) const {
  int first = 0;
  std::vector<double> values;
  knot_basis().evaluate(t, first, values);
  Vec3 x = Vec3::Zero();
  for (std::size_t i = 0; i < values.size(); ++i) x += values[i] * x_.row(first + static_cast<Eigen::Index>(i)).transpose();
  return x;
}

Vec3 VariationalCurve::tangent(double t) const {
  int first = 0;
  std::vector<std::vector<double>> d;
  knot_basis().derivatives(t, 1, first, d);
  Vec3 x = Vec3::Zero();
  for (std::size_t i = 0; i < d[1].size(); ++i) x += d[1][i] * x_.row(first + static_cast<Eigen::Index>(i)).transpose();
  return x / length_;
}

std::vector<Vec3> VariationalCurve::sample(int count) const {
  FAIRSHAPE_ASSERT(count >= 2, "a curve is sampled into two points at least");
  std::vector<Vec3> out;
  for (int k = 0; k < count; ++k) out.push_back(position(static_cast<double>(k) / (count - 1)));
  return out;
}

SparseMatrix curve_square_root(const VariationalCurve& c, const CurveEnergy& e) {
  validate(e);
  const int r = c.shape().degree;
  const double L = c.design_length();
  // dX/dσ = X'/L, d²X/dσ² = X''/L², dσ = L dt: E = ∫ α/L |X'|² + β/L³ |X''|² dt.
  const double weight[2] = {2 * e.alpha / L, 2 * e.beta / (L * L * L)};
  const GaussRule g = gauss_legendre(r + 1);
  Triplets t;
  int rows = 0, first = 0;
  std::vector<std::vector<double>> d;
  for (const CurveSpan& leaf : c.basis().leaf_cells())
    for (std::size_t q = 0; q < g.nodes.size(); ++q) {
      const double h = leaf.t1 - leaf.t0, tq = leaf.t0 + g.nodes[q] * h, w = g.weights[q] * h;
      c.knot_basis().derivatives(tq, 2, first, d);
      for (int order = 1; order <= 2; ++order) {
        if (weight[order - 1] == 0) continue;
        const double root = std::sqrt(w * weight[order - 1]);
        for (std::size_t i = 0; i < d[order].size(); ++i) t.emplace_back(rows, first + static_cast<int>(i), root * d[order][i]);
        ++rows;
      }
    }
  SparseMatrix K(rows, c.knot_basis().size());
  K.setFromTriplets(t.begin(), t.end());
  return K * c.basis().to_knot_basis();
}

SparseMatrix curve_hessian(const VariationalCurve& c, const CurveEnergy& e) {
  const SparseMatrix K = curve_square_root(c, e);
  return SparseMatrix(K.transpose() * K);
}

double curve_energy(const VariationalCurve& c, const CurveEnergy& e) {
  return 0.5 * (curve_square_root(c, e) * c.control_points()).squaredNorm();
}

ConstraintRows curve_constraint_rows(const VariationalCurve& c, const std::vector<CurveConstraint>& constraints) {
  ConstraintRows out;
  out.C.resize(static_cast<Eigen::Index>(constraints.size()), 3);
  Triplets t;
  int first = 0;
  std::vector<std::vector<double>> d;
  for (std::size_t k = 0; k < constraints.size(); ++k) {
    const CurveConstraint& cc = constraints[k];
    const std::string what = cc.label.empty() ? std::string("curve constraint") : cc.label;
    if (!(cc.t >= 0 && cc.t <= 1)) throw InvalidInput(what + ": t must lie in [0, 1]");
    if (!cc.target.allFinite()) throw InvalidInput(what + ": target is not finite");
    const bool tangent = cc.kind == CurveConstraint::Kind::Tangent;
    c.knot_basis().derivatives(cc.t, tangent ? 1 : 0, first, d);
    const double scale = tangent ? 1 / c.design_length() : 1.0;
    for (std::size_t i = 0; i < d.back().size(); ++i)
      t.emplace_back(static_cast<int>(k), first + static_cast<int>(i), scale * d.back()[i]);
    out.C.row(static_cast<Eigen::Index>(k)) = cc.target.transpose();
  }
  SparseMatrix A(static_cast<Eigen::Index>(constraints.size()), c.knot_basis().size());
  A.setFromTriplets(t.begin(), t.end());
  out.A = A * c.basis().to_knot_basis();
  return out;
}

qp::QuadraticProgram assemble(const VariationalCurve& c, const CurveEnergy& e, const std::vector<CurveConstraint>& constraints) {
  qp::QuadraticProgram p;
  p.K = curve_square_root(c, e);
  p.H = p.K.transpose() * p.K;
  p.f = Eigen::MatrixXd::Zero(c.dof_count(), 3);
  ConstraintRows rows = curve_constraint_rows(c, constraints);
  p.A = std::move(rows.A);
  p.b = std::move(rows.C);
  return p;
}

namespace {
double error_of(const VariationalCurve& c, const CurveConstraint& cc) {
  const Vec3 x = cc.kind == CurveConstraint::Kind::Point ? c.position(cc.t) : c.tangent(cc.t);
  return (x - cc.target).norm();
}
}  // namespace

double max_error(const VariationalCurve& c, const std::vector<CurveConstraint>& constraints) {
  double worst = 0;
  for (const CurveConstraint& cc : constraints) worst = std::max(worst, error_of(c, cc));
  return worst;
}

std::vector<double> leaf_errors(const VariationalCurve& c, const std::vector<CurveConstraint>& constraints) {
  const std::vector<CurveSpan>& leaves = c.basis().leaf_cells();
  std::vector<double> out(leaves.size(), 0.0);
  for (const CurveConstraint& cc : constraints) {
    const std::size_t k = static_cast<std::size_t>(&c.basis().leaf_cell_at(cc.t) - leaves.data());
    out[k] = std::max(out[k], error_of(c, cc));
  }
  return out;
}

}  // namespace fairshape::bspline
