// Constrained quadratic programs shared by the QP solver tests (Welch & Witkin §4.3).
#pragma once

#include <cmath>
#include <utility>
#include <vector>

#include "fairshape/bspline/hierarchical_surface.h"
#include "fairshape/bspline/surface_constraints.h"
#include "fairshape/bspline/thin_plate_energy.h"
#include "fairshape/qp/quadratic_program.h"

namespace fairshape::test {

// A 6×6 bicubic sheet with a point constraint at each corner region, a lifted center point and
// a curve constraint across it: bending energy, flat rest position.
struct SheetProblem {
  bspline::HierarchicalSurface s{{6, 6, 3, false}};
  qp::QuadraticProgram qp;
  int curve_row_count = 0;
  SheetProblem() {
    s.refine({{0, 2, 2}, {0, 3, 2}, {0, 2, 3}, {0, 3, 3}});
    bspline::TensionWeights w;
    w.alpha = 0.1 * Eigen::Matrix2d::Identity();
    qp.H = bspline::thin_plate_hessian(s, w, Backend::Optimized);
    qp.K = bspline::thin_plate_square_root(s, w);
    qp.f = Eigen::MatrixXd::Zero(s.dof_count(), 3);
    std::vector<bspline::ConstraintRows> parts;
    for (const auto& [u, v] : std::vector<std::pair<double, double>>{{0.5, 0.5}, {5.5, 0.5}, {0.5, 5.5}, {5.5, 5.5}})
      parts.push_back(bspline::point_rows(s, u, v, Vec3(u, v, 0)));
    parts.push_back(bspline::point_rows(s, 3, 3, Vec3(3, 3, 1.5)));
    bspline::CurveAttachment c;
    for (int k = 0; k <= 10; ++k) {
      const double u = 1 + 0.4 * k;
      c.uv.emplace_back(u, 2.0);
      c.space.emplace_back(u, 2.0, 0.5 * std::sin(0.3 * k));
    }
    const bspline::ConstraintRows curve = bspline::curve_rows(s, c, bspline::CurveQuadrature::Exact);
    curve_row_count = static_cast<int>(curve.A.rows());
    parts.push_back(curve);
    const bspline::ConstraintRows all = bspline::stack(parts, s.dof_count());
    qp.A = all.A;
    qp.b = all.C;
  }
};

}  // namespace fairshape::test
