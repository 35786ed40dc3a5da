#include "fairshape/curve_design/curve_constraint.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "fairshape/core/config.h"
#include "fairshape/core/error.h"

namespace fairshape {

Eigen::VectorXd segment_lengths(const MatrixX3& X, bool closed) {
  const Eigen::Index n = X.rows(), m = closed ? n : n - 1;
  Eigen::VectorXd l(std::max<Eigen::Index>(m, 0));
  for (Eigen::Index i = 0; i < m; ++i) l[i] = (X.row((i + 1) % n) - X.row(i)).norm();
  return l;
}

SegmentLengths::SegmentLengths(Eigen::VectorXd lengths, bool closed)
    : lengths_(std::move(lengths)), closed_(closed),
      n_points_(static_cast<int>(closed ? lengths_.size() : lengths_.size() + 1)) {
  if (lengths_.size() == 0) throw InvalidInput("length constraints: the curve has no segment");
  const double scale = lengths_.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < lengths_.size(); ++i)
    if (!(lengths_[i] > 1e-12 * scale))
      throw InvalidInput("length constraints: segment " + std::to_string(i) + " (points " + std::to_string(i) +
                         "-" + std::to_string((i + 1) % n_points_) +
                         ") has zero length; every segment needs a length to preserve (remove repeated points)");
}

ConstraintRow SegmentLengths::touched(int i) const {
  ConstraintRow r;
  r.row = i;
  r.size = 2;
  r.points = {i, (i + 1) % n_points_};
  return r;
}

void SegmentLengths::evaluate_at(ConstraintRow& r, const Vec3* x) const {
  const int i = r.row;
  const Vec3 d = x[1] - x[0];
  r.value = d.squaredNorm() - lengths_[i] * lengths_[i];
  r.gradient = {-2 * d, 2 * d};
}

void SegmentLengths::add_row_hessian(int i, double scale, const MatrixX3& /*X*/, Triplets& out) const {
  const int j = (i + 1) % n_points_;
  for (int c = 0; c < 3; ++c) {
    out.emplace_back(3 * i + c, 3 * i + c, 2 * scale);
    out.emplace_back(3 * j + c, 3 * j + c, 2 * scale);
    out.emplace_back(3 * i + c, 3 * j + c, -2 * scale);
    out.emplace_back(3 * j + c, 3 * i + c, -2 * scale);
  }
}

PinnedPoints::PinnedPoints(std::vector<int> points, MatrixX3 targets)
    : points_(std::move(points)), targets_(std::move(targets)) {
  FAIRSHAPE_ASSERT(targets_.rows() == static_cast<Eigen::Index>(points_.size()), "one target per pinned point");
}

// Rows 3k, 3k+1, 3k+2 hold pinned point k's x, y and z.
ConstraintRow PinnedPoints::touched(int row) const {
  ConstraintRow r;
  r.row = row;
  r.size = 1;
  r.points = {points_[row / 3], points_[row / 3]};
  return r;
}

void PinnedPoints::evaluate_at(ConstraintRow& r, const Vec3* x) const {
  const int k = r.row / 3, c = r.row % 3;
  r.value = x[0][c] - targets_(k, c);
  r.gradient[0] = Vec3::Unit(c);
}

double PinnedPoints::relative_error(const MatrixX3& X, double curve_length) const {
  double worst = 0;
  for (std::size_t k = 0; k < points_.size(); ++k)
    worst = std::max(worst, (X.row(points_[k]) - targets_.row(static_cast<Eigen::Index>(k))).norm());
  return worst / curve_length;
}

std::pair<int, int> FixedTangents::chord(int p, int n, bool closed) {
  if (closed) return {(p + n - 1) % n, (p + 1) % n};
  return {std::max(p - 1, 0), std::min(p + 1, n - 1)};
}

FixedTangents::FixedTangents(std::vector<int> points, MatrixX3 directions, int n_points, bool closed)
    : points_(std::move(points)), directions_(std::move(directions)), scales_(points_.size(), 1.0) {
  FAIRSHAPE_ASSERT(directions_.rows() == static_cast<Eigen::Index>(points_.size()), "one direction per point");
  const Eigen::Index m = directions_.rows();
  normals_[0].resize(m, 3);
  normals_[1].resize(m, 3);
  for (Eigen::Index k = 0; k < m; ++k) {
    const int p = points_[static_cast<std::size_t>(k)];
    if (p < 0 || p >= n_points)
      throw InvalidInput("tangent: point " + std::to_string(p) + " is not on the curve (0.." + std::to_string(n_points - 1) + ")");
    const double len = directions_.row(k).norm();
    if (!(len > 0) || !std::isfinite(len)) throw InvalidInput("tangent: the direction at point " + std::to_string(p) + " is zero or not finite");
    const Vec3 t = directions_.row(k).transpose() / len;
    directions_.row(k) = t.transpose();
    // Two unit normals of t: the axis least aligned with t, made orthogonal, and t × that.
    Eigen::Index axis = 0;
    t.cwiseAbs().minCoeff(&axis);
    const Vec3 n0 = (Vec3::Unit(axis) - t[axis] * t).normalized();
    normals_[0].row(k) = n0.transpose();
    normals_[1].row(k) = t.cross(n0).transpose();
    chords_.push_back(chord(p, n_points, closed));
  }
}

void FixedTangents::set_scales(const MatrixX3& X) {
  for (std::size_t k = 0; k < chords_.size(); ++k) scales_[k] = std::max((X.row(chords_[k].second) - X.row(chords_[k].first)).norm(), 1e-300);
}

// Rows 2k and 2k + 1: normal 0 and 1 of point k's direction against its chord.
ConstraintRow FixedTangents::touched(int row) const {
  ConstraintRow r;
  r.row = row;
  r.size = 2;
  r.points = {chords_[row / 2].first, chords_[row / 2].second};
  return r;
}

void FixedTangents::evaluate_at(ConstraintRow& r, const Vec3* x) const {
  const Vec3 n = normals_[r.row % 2].row(r.row / 2).transpose();
  r.value = n.dot(x[1] - x[0]);
  r.gradient = {-n, n};
}

double FixedTangents::relative_error(const MatrixX3& X, double /*curve_length*/) const {
  double worst = 0;
  for (std::size_t k = 0; k < chords_.size(); ++k) {
    const Vec3 d = (X.row(chords_[k].second) - X.row(chords_[k].first)).transpose();
    const Vec3 t = directions_.row(static_cast<Eigen::Index>(k)).transpose();
    worst = std::max(worst, std::atan2(d.cross(t).norm(), d.dot(t)));
  }
  return worst;
}

TotalLength::TotalLength(const Eigen::VectorXd& reference, double target, bool closed)
    : target_(target), closed_(closed), n_points_(static_cast<int>(closed ? reference.size() : reference.size() + 1)) {
  if (reference.size() == 0) throw InvalidInput("total_length: the curve has no segment");
  if (!(target_ > 0) || !std::isfinite(target_))
    throw InvalidInput("total_length: the length to keep must be a positive finite number, not " + format_default(target_));
}

ConstraintRow TotalLength::touched(int row) const {
  ConstraintRow r;
  r.row = row;
  r.size = n_points_;
  r.dense = true;
  return r;
}

void TotalLength::evaluate_at(ConstraintRow&, const Vec3*) const {
  FAIRSHAPE_ASSERT(false, "total_length is a dense row: evaluate it on the whole curve");
}

// f = Σ|d_i| − L, ∂f/∂X_i = u_{i−1} − u_i (u the unit segment directions).
ConstraintRow TotalLength::evaluate(int row, const MatrixX3& X) const {
  ConstraintRow r = touched(row);
  const int n = n_points_, segments = closed_ ? n : n - 1;
  r.dense_gradient = MatrixX3::Zero(n, 3);
  double total = 0;
  for (int i = 0; i < segments; ++i) {
    const int j = (i + 1) % n;
    const Eigen::RowVector3d d = X.row(j) - X.row(i);
    const double len = d.norm();
    total += len;
    if (len > 0) {  // a zero-length segment has no direction: its subgradient 0 is taken
      r.dense_gradient.row(i) -= d / len;
      r.dense_gradient.row(j) += d / len;
    }
  }
  r.value = total - target_;
  return r;
}

// ∇²|d| = (I − u uᵀ)/|d| on segment i's two points, with the signs of [1 −1; −1 1]; all nine
// entries of every block are emitted (zeros too), so the pattern does not depend on X.
void TotalLength::add_row_hessian(int /*row*/, double scale, const MatrixX3& X, Triplets& out) const {
  const int n = n_points_, segments = closed_ ? n : n - 1;
  for (int i = 0; i < segments; ++i) {
    const int j = (i + 1) % n;
    const Vec3 d = (X.row(j) - X.row(i)).transpose();
    const double len = d.norm();
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    if (len > 0) H = (Eigen::Matrix3d::Identity() - d * d.transpose() / (len * len)) * (scale / len);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        out.emplace_back(3 * i + a, 3 * i + b, H(a, b));
        out.emplace_back(3 * j + a, 3 * j + b, H(a, b));
        out.emplace_back(3 * i + a, 3 * j + b, -H(a, b));
        out.emplace_back(3 * j + a, 3 * i + b, -H(a, b));
      }
  }
}

double TotalLength::length_error(const MatrixX3& X) const {
  return std::abs(segment_lengths(X, closed_).sum() - target_) / target_;
}

}  // namespace fairshape
