// Constraints on a polyline's points, each a list of scalar rows f_r(X) = 0: the per-segment
// length constraints of Sauvage, Hahmann and Bonneau, "Length preserving multiresolution
// editing of curves" (§2, f_i = |Δc_i|² − l_i²), pinned points, tangents — rows that touch at
// most two points — and the paper's alternative to per-segment lengths, one fixed total length
// (a dense row over every point). Rows give their value, gradient and (for Newton-type steps
// and the second-order check) Hessian, so every solver works with any registered constraint.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "fairshape/core/registry.h"
#include "fairshape/core/types.h"

namespace fairshape {

struct ConstraintRow {
  int row = 0;                     // index within its constraint
  int size = 0;                    // points touched: 1 or 2, or every point of the curve (dense)
  std::array<int, 2> points{};     // sparse rows: the points touched
  double value = 0;                // f_r(X)
  std::array<Vec3, 2> gradient{};  // sparse rows: ∂f_r/∂X_point
  //! A dense row touches every point 0..size−1 (a total length): its gradient is one row per
  //! point. The banded KKT factor borders such rows instead of ordering them into the band.
  bool dense = false;
  MatrixX3 dense_gradient;
  int point(int k) const { return dense ? k : points[static_cast<std::size_t>(k)]; }
  Vec3 grad(int k) const { return dense ? Vec3(dense_gradient.row(k).transpose()) : gradient[static_cast<std::size_t>(k)]; }
};

class CurveConstraint {
 public:
  virtual ~CurveConstraint() = default;
  virtual int rows() const = 0;
  //! The points row `row` touches (size and points set; value and gradient left empty).
  virtual ConstraintRow touched(int row) const = 0;
  //! Fills value and gradient from the touched points' positions x[0], x[1] (Ceres hands
  //! over trial positions this way, not a whole curve). Sparse rows only.
  virtual void evaluate_at(ConstraintRow& r, const Vec3* x) const = 0;
  //! The row at the curve X (dense rows read every point).
  virtual ConstraintRow evaluate(int row, const MatrixX3& X) const {
    ConstraintRow r = touched(row);
    const Vec3 x[2] = {X.row(r.points[0]).transpose(), X.row(r.points[1]).transpose()};
    evaluate_at(r, x);
    return r;
  }
  //! True when some row touches every point (ConstraintRow::dense).
  virtual bool has_dense_rows() const { return false; }
  //! Adds scale·∇²f_row at the curve X to `out` over interleaved unknowns 3·point + coordinate.
  //! Rows whose Hessian depends on X (a dense row's) emit the same entries in the same order
  //! at every X, zeros included, so a factor can reuse their slots.
  virtual void add_row_hessian(int /*row*/, double /*scale*/, const MatrixX3& /*X*/, Triplets& /*out*/) const {}
  //! False when ∇²f_row depends on X (the factor then re-reads it at every iterate).
  virtual bool constant_hessian() const { return true; }
  //! A typical |f_row| (so scaled rows are dimensionless: Ceres's penalty uses f/scale).
  virtual double row_scale(int /*row*/) const { return 1.0; }
  //! How far X is from meeting this constraint, dimensionless (pins: distance over the curve's
  //! length; tangents: the angle in radians). Segment lengths have their own measure.
  virtual double relative_error(const MatrixX3& /*X*/, double /*curve_length*/) const { return 0; }
};

// f_i = |X_{i+1} − X_i|² − l_i² for every segment (closed curves wrap).
class SegmentLengths final : public CurveConstraint {
 public:
  //! \throw InvalidInput naming the first segment of (near) zero length.
  SegmentLengths(Eigen::VectorXd lengths, bool closed);
  int rows() const override { return static_cast<int>(lengths_.size()); }
  ConstraintRow touched(int row) const override;
  void evaluate_at(ConstraintRow& r, const Vec3* x) const override;
  void add_row_hessian(int row, double scale, const MatrixX3& X, Triplets& out) const override;
  double row_scale(int row) const override { return lengths_[row] * lengths_[row]; }
  const Eigen::VectorXd& lengths() const { return lengths_; }
  bool closed() const { return closed_; }

 private:
  Eigen::VectorXd lengths_;
  bool closed_;
  int n_points_;
};

// X_p = target_p for a set of points (three rows each).
class PinnedPoints final : public CurveConstraint {
 public:
  PinnedPoints(std::vector<int> points, MatrixX3 targets);
  int rows() const override { return 3 * static_cast<int>(points_.size()); }
  ConstraintRow touched(int row) const override;
  void evaluate_at(ConstraintRow& r, const Vec3* x) const override;
  double relative_error(const MatrixX3& X, double curve_length) const override;
  const std::vector<int>& points() const { return points_; }
  const MatrixX3& targets() const { return targets_; }

 private:
  std::vector<int> points_;
  MatrixX3 targets_;
};

// The tangent at a point held along a direction t: the chord through its neighbours
// d = X_b − X_a (a = p − 1, b = p + 1; one-sided at an open curve's ends) is kept ⟂ to two
// unit normals of t, two linear rows n·d = 0 that leave its length to the other constraints.
// With the segment lengths kept, a tangent that starts within 90° of t cannot flip to −t
// without passing through a zero-length chord; relative_error reports the angle to t.
class FixedTangents final : public CurveConstraint {
 public:
  //! 	hrow InvalidInput for a point off the curve or a zero direction.
  FixedTangents(std::vector<int> points, MatrixX3 directions, int n_points, bool closed);
  int rows() const override { return 2 * static_cast<int>(points_.size()); }
  ConstraintRow touched(int row) const override;
  void evaluate_at(ConstraintRow& r, const Vec3* x) const override;
  double row_scale(int row) const override { return scales_[row / 2]; }
  double relative_error(const MatrixX3& X, double curve_length) const override;
  //! The chord (a, b) whose direction stands for point p's tangent.
  static std::pair<int, int> chord(int p, int n_points, bool closed);
  void set_scales(const MatrixX3& X);  // typical |d| per point, from a curve of the right lengths
  const std::vector<std::pair<int, int>>& chords() const { return chords_; }
  const MatrixX3& directions() const { return directions_; }  // unit, one row per point

 private:
  std::vector<int> points_;
  std::vector<std::pair<int, int>> chords_;
  MatrixX3 directions_, normals_[2];
  std::vector<double> scales_;
};

// The alternative to per-segment lengths the paper discusses: one row f(X) = Σ_i |X_{i+1} − X_i|
// − L over every segment (closed curves wrap), so individual segments may stretch while the
// curve's total length stays L. Its gradient touches every point (a dense row) and its Hessian,
// Σ_i (I − u_i u_iᵀ)/|d_i| on the block pattern [1 −1; −1 1] of segment i (u_i = d_i / |d_i|),
// depends on X but stays block-tridiagonal, inside the banded KKT order's band.
class TotalLength final : public CurveConstraint {
 public:
  //! `reference`: the reference curve's segment lengths (scale and messages); `target` L.
  //! \throw InvalidInput for a target that is not a positive finite length, or a curve without segments.
  TotalLength(const Eigen::VectorXd& reference, double target, bool closed);
  int rows() const override { return 1; }
  ConstraintRow touched(int row) const override;
  void evaluate_at(ConstraintRow& r, const Vec3* x) const override;  // not for dense rows: asserts
  ConstraintRow evaluate(int row, const MatrixX3& X) const override;
  bool has_dense_rows() const override { return true; }
  void add_row_hessian(int row, double scale, const MatrixX3& X, Triplets& out) const override;
  bool constant_hessian() const override { return false; }
  double row_scale(int /*row*/) const override { return target_; }
  double target() const { return target_; }
  bool closed() const { return closed_; }
  //! |L(X) − L| / L.
  double length_error(const MatrixX3& X) const;

 private:
  double target_;
  bool closed_;
  int n_points_;
};

//! The lengths of a polyline's segments (closed curves include the closing one).
Eigen::VectorXd segment_lengths(const MatrixX3& points, bool closed);

}  // namespace fairshape
