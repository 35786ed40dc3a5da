// A variational space curve: Welch & Witkin ("Variational surface modeling", §5) make curves
// "first-class variational objects" that constraints control, and join sheets along them. Here
// a clamped hierarchical B-spline X(t), t ∈ [0, 1], of degree r (2..5): `spans` equal base
// spans, refined locally like the sheets (bspline/hierarchical_curve_basis.h), with unknowns
// q (dofs × 3) minimizing its own fairness energy
//   E = ∫ α |dX/dσ|² + β |d²X/dσ²|² dσ,   σ = L t   (the 1-D thin plate under tension, eq. 4)
// subject to point constraints X(t₀) = x and tangent constraints dX/dσ(t₀) = d.
// Design units: σ is t scaled by the length L of the polyline the curve was first fitted to, so
// E and the tangents are world quantities and the same design at 8 or 64 spans is one problem
// (as the sheets' design units, SheetShape::span_size): the energy does not change with `spans`
// or with refinement for a curve every resolution contains.
#pragma once

#include <string>
#include <vector>

#include "fairshape/bspline/hierarchical_curve_basis.h"
#include "fairshape/bspline/surface_constraints.h"
#include "fairshape/qp/quadratic_program.h"

namespace fairshape::bspline {

struct CurveShape {
  int spans = 16;  // base spans (before refinement)
  int degree = 3;
};

struct CurveEnergy {
  double alpha = 0;     // stretching (tension)
  double beta = 1e-3;   // bending
};
//! \throw InvalidInput for a negative or non-finite weight, or both zero (nothing to minimize).
void validate(const CurveEnergy& e);

struct CurveConstraint {
  enum class Kind { Point, Tangent } kind = Kind::Point;
  double t = 0;                 // ∈ [0, 1]
  Vec3 target = Vec3::Zero();   // the point, or dX/dσ (design units: per unit length)
  std::string label;            // for messages: "constraints[4]"
};

class VariationalCurve {
 public:
  //! The least-squares fit of a polyline of points equally spaced in t: the control points
  //! minimizing Σ_k |X(t_k) − P_k|². A polyline with fewer than n points is first subdivided
  //! evenly (the same path with the same t), so the fit is determined whatever the samples; one
  //! sampled from a curve of this space is reproduced exactly. L is the polyline's length.
  //! \throw InvalidInput for spans outside [1, kMaxSpans], a degree outside [2, 5], fewer than
  //! two points, a non-finite point or a polyline of zero length.
  VariationalCurve(const CurveShape& shape, const std::vector<Vec3>& polyline);
  //! Given control points (n × 3, the unrefined basis) and design length L > 0.
  VariationalCurve(const CurveShape& shape, Eigen::MatrixXd control_points, double design_length);

  const CurveShape& shape() const { return shape_; }
  const HierarchicalCurveBasis& basis() const { return basis_; }
  //! The clamped basis on the leaf cells' breaks, and X's coefficients in it (R q).
  const ClampedKnotBasis& knot_basis() const { return basis_.knot_basis(); }
  const Eigen::MatrixXd& knot_coefficients() const { return x_; }
  int dof_count() const { return basis_.dof_count(); }
  double design_length() const { return length_; }
  const Eigen::MatrixXd& control_points() const { return q_; }
  void set_control_points(Eigen::MatrixXd q);
  //! Refines the given leaf cells (HierarchicalCurveBasis::refine); the curve does not change
  //! (its new control points are the exact fit of the old X in the finer space, which contains
  //! it). Returns the number of spans added. \throw InvalidInput as HierarchicalCurveBasis::refine.
  int refine(const std::vector<CurveSpan>& cells);
  Vec3 position(double t) const;
  //! dX/dσ at t: the derivative in design units.
  Vec3 tangent(double t) const;
  //! `count` ≥ 2 points equally spaced in t.
  std::vector<Vec3> sample(int count) const;

 private:
  CurveShape shape_;
  HierarchicalCurveBasis basis_;
  double length_ = 1;
  Eigen::MatrixXd q_, x_;  // unknowns, and X's knot-basis coefficients R q
};

//! K with KᵀK = H and ½ qᵀHq = E per coordinate: the quadrature rows √(2wα/L) N'(t_g) and
//! √(2wβ/L³) N''(t_g), r + 1 Gauss points per leaf cell (exact: the integrand has degree
//! ≤ 2r − 2), N the knot basis mapped by R.
SparseMatrix curve_square_root(const VariationalCurve& c, const CurveEnergy& e);
SparseMatrix curve_hessian(const VariationalCurve& c, const CurveEnergy& e);
//! E of the curve's control points (summed over x, y, z).
double curve_energy(const VariationalCurve& c, const CurveEnergy& e);

//! One row per constraint, shared by x, y and z. \throw InvalidInput naming the constraint's
//! label for t outside [0, 1] or a non-finite target.
ConstraintRows curve_constraint_rows(const VariationalCurve& c, const std::vector<CurveConstraint>& constraints);
//! The curve's own program: H, K, f = 0 and its rows (a curve no sheet is joined to is solved
//! alone; a joined one contributes these blocks to bspline/joined_design.h).
qp::QuadraticProgram assemble(const VariationalCurve& c, const CurveEnergy& e, const std::vector<CurveConstraint>& constraints);
//! The largest |X(t₀) − x| or |dX/dσ(t₀) − d| over the constraints (0 for none).
double max_error(const VariationalCurve& c, const std::vector<CurveConstraint>& constraints);
//! The same per leaf cell (the cell holding t₀; 0 where no constraint sits), in leaf order:
//! what refinement reads.
std::vector<double> leaf_errors(const VariationalCurve& c, const std::vector<CurveConstraint>& constraints);

}  // namespace fairshape::bspline
