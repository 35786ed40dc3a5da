// Builders shared by the surface-edit tests: the direct solver and the detail-preserving
// problem (stretch + bend of the deformation, α = 0.1, β = 1) with propagated constraints.
#pragma once

#include <memory>

#include "fairshape/design/edit_solve.h"
#include "fairshape/design/multires_constraints.h"
#include "fairshape/energy/local_quadratic.h"
#include "fairshape/experiment/components.h"

namespace fairshape::test {

inline std::unique_ptr<Solver> cholesky() {
  Config none;
  return components().solvers.create("cholesky", Backend::Optimized, none);
}

inline EditProblem detail_preserving(const MultiresSurface& h, int level, const DesignConstraints& dc) {
  EditProblem p;
  p.H = stretch_bend_hessian(h.mesh(level), {0.1, 1.0}, Backend::Optimized);
  p.g = Eigen::MatrixXd::Zero(p.H.rows(), 3);
  p.constraints = propagate_constraints(h, level, dc);
  return p;
}

}  // namespace fairshape::test
