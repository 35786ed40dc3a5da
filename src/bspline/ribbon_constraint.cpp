#include "fairshape/bspline/ribbon_constraint.h"

#include "fairshape/bspline/mortar_curve.h"
#include "fairshape/core/error.h"

namespace fairshape::bspline {

// The cross rows are the tangent-continuity rows (mortar_curve.h) of the sheet against the
// traced surface: ∂w/∂n_out + ∂w₀/∂n₀_out = 0 with the sheet's outward normal to the left and the
// traced side's to the right reads ∂w/∂n = ∂w₀/∂n. One integration, one multiplier space (the
// finer side's: the sheet's, which is never coarser than a surface it was traced on).
ConstraintRows cross_tangent_rows(const HierarchicalSurface& s, const std::vector<Eigen::Vector2d>& uv, const Vec3& cross,
                                  const SurfaceTrace* traced) {
  if (!cross.allFinite()) throw InvalidInput("ribbon constraint: the cross tangent is not finite");
  const JointSide sheet{&s, uv, /*keep_left=*/false};  // outward: to the left
  ConstraintRows out;
  if (traced) {
    const JointSide other{&traced->surface, uv, /*keep_left=*/true};  // outward: to the right
    const TangentContinuityRows rows = tangent_continuity_rows(sheet, other);
    out.A = rows.first;
    out.C = -(rows.second * traced->P);
    return out;
  }
  // A fixed target: every row is a weighted mean of ∂w/∂n (rows divided by ∫ψ_j), so its target
  // is the vector itself.
  out.A = tangent_continuity_rows(sheet, sheet).first;
  out.C = cross.transpose().replicate(out.A.rows(), 1);
  return out;
}

Vec3 cross_tangent_at(const HierarchicalSurface& s, const Eigen::MatrixXd& P, const std::vector<Eigen::Vector2d>& uv, double t) {
  return outward_derivative(JointSide{&s, uv, /*keep_left=*/false}, P, t);
}

}  // namespace fairshape::bspline
