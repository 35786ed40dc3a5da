// Constraints on a polyline's points, each a list of scalar rows f_r(X) = 0 that touch at
// most two points: the per-segment length constraints of Sauvage, Hahmann and Bonneau,
// "Length preserving multiresolution editing of curves" (§2, f_i = |Δc_i|² − l_i²), and pinned
// points. Rows give their value, gradient and (for the Newton variant of the linearized loop)
// Hessian, so the Lagrange loop and Ceres work with any registered constraint.
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
  int size = 0;                    // points touched (1 or 2)
  std::array<int, 2> points{};
  double value = 0;                // f_r(X)
  std::array<Vec3, 2> gradient{};  // ∂f_r/∂X_point
};

class CurveConstraint {
 public:
  virtual ~CurveConstraint() = default;
  virtual int rows() const = 0;
  //! The points row `row` touches (size and points set; value and gradient left empty).
  virtual ConstraintRow touched(int row) const = 0;
  //! Fills value and gradient from the touched points' positions x[0], x[1] (Ceres hands
  //! over trial positions this way, not a whole curve).
  virtual void evaluate_at(ConstraintRow& r, const Vec3* x) const = 0;
  ConstraintRow evaluate(int row, const MatrixX3& X) const {
    ConstraintRow r = touched(row);
    const Vec3 x[2] = {X.row(r.points[0]).transpose(), X.row(r.points[1]).transpose()};
    evaluate_at(r, x);
    return r;
  }
  //! Adds scale·∇²f_row to `out` over interleaved unknowns 3·point + coordinate.
  virtual void add_row_hessian(int /*row*/, double /*scale*/, Triplets& /*out*/) const {}
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
  void add_row_hessian(int row, double scale, Triplets& out) const override;
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

 private:
  std::vector<int> points_;
  std::vector<std::pair<int, int>> chords_;
  MatrixX3 directions_, normals_[2];
  std::vector<double> scales_;
};

//! The lengths of a polyline's segments (closed curves include the closing one).
Eigen::VectorXd segment_lengths(const MatrixX3& points, bool closed);

}  // namespace fairshape
