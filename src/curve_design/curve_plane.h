// Planar curves stay planar (papers/sauvage/README.md, "Planar curves"). Sauvage, Hahmann and
// Bonneau edit curves in the plane (every figure of the paper is planar), but their problem
// (§3, eq. 2) has three unknowns per point: at a wrinkled planar curve the bending energy has
// negative curvature out of the plane, so a solver that follows negative curvature (or just
// rounding) lifts the curve out of it, and its drawing in the plane is shorter than the lengths
// it certifies. A planar problem is therefore solved in its plane: one linear row per free
// point, n·(X_p − o) = 0, pins the normal component. The same rows make the second-order check
// (second_order.h) look only at in-plane directions: null(J) then lies in the plane.
#pragma once

#include <vector>

#include "fairshape/core/types.h"
#include "fairshape/curve_design/curve_constraint.h"

namespace fairshape {

//! Points within this fraction of the curves' bounding-box diagonal of one plane count as
//! planar: far above rounding of coordinates written with 17 digits, far below any shape.
inline constexpr double kPlanarTolerance = 1e-9;

struct CurvePlane {
  bool planar = false;     // every point lies within kPlanarTolerance·size of the plane
  Vec3 origin = Vec3::Zero(), normal = Vec3::UnitZ();
  double size = 0;         // bounding-box diagonal of the points the plane was fitted to
  double deviation = 0;    // their largest distance from the plane
};

//! The least-squares plane of every point of `curves` (centroid; normal: the covariance's
//! eigenvector of the smallest eigenvalue). Collinear points leave the normal free: it is taken
//! ⟂ to the line and as close as possible to z, the side the explicit step bulges to
//! (explicit_length.h).
CurvePlane fit_plane(const std::vector<const MatrixX3*>& curves);

//! max_p |n·(X_p − o)|.
double distance_from_plane(const MatrixX3& X, const CurvePlane& plane);

// n·(X_p − o) = 0 for each listed point: the point stays in the plane (one linear row each).
class InPlane final : public CurveConstraint {
 public:
  InPlane(std::vector<int> points, const CurvePlane& plane);
  int rows() const override { return static_cast<int>(points_.size()); }
  ConstraintRow touched(int row) const override;
  void evaluate_at(ConstraintRow& r, const Vec3* x) const override;
  double row_scale(int /*row*/) const override { return scale_; }
  //! The largest distance from the plane over the curve's length.
  double relative_error(const MatrixX3& X, double curve_length) const override;
  const std::vector<int>& points() const { return points_; }
  const CurvePlane& plane() const { return plane_; }

 private:
  std::vector<int> points_;
  CurvePlane plane_;
  double scale_;
};

//! The points of an n-point curve that need an in-plane row given the other constraints, so
//! that no row is a combination of others (a dependent row makes the KKT matrix singular):
//! none for pinned points (their three rows hold the normal component already), and one per
//! group of points joined by tangent chords (a tangent in the plane holds the chord's normal
//! component, so one in-plane row per group places the whole group).
std::vector<int> in_plane_points(int n_points, const std::vector<const CurveConstraint*>& constraints);

//! Whether `constraints` can hold in `plane`: pins on it and tangent directions in it.
bool constraints_in_plane(const std::vector<const CurveConstraint*>& constraints, const CurvePlane& plane);

}  // namespace fairshape
