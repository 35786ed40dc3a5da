#include "curve_design/curve_constraint.h"

#include <string>

#include "core/error.h"

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

void SegmentLengths::add_row_hessian(int i, double scale, Triplets& out) const {
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

}  // namespace fairshape
