// The registries of the curve editor: energies, constraint kinds and length solvers, each
// selectable by name in a config (`fairshape list` shows them with their options).
#pragma once

#include <memory>
#include <vector>

#include "fairshape/core/registry.h"
#include "fairshape/curve_design/curve_constraint.h"
#include "fairshape/curve_design/curve_energy.h"
#include "fairshape/curve_design/length_solver.h"
#include "fairshape/mesh/polyline.h"

namespace fairshape {

// What a constraint kind may refer to when it is built for one edit.
struct CurveEditContext {
  const Polyline& reference;        // C_R: its segment lengths are the ones to keep
  const MatrixX3& edited;           // C_D: the curve after the user's edit, before any fixing
  std::vector<int> moved_points;    // fine-level indices of the control points the user moved
  //! The segment lengths every edit keeps: the original curve's, not the previous edit's result
  //! (a drag of many steps would otherwise carry each step's rounding into the next).
  const Eigen::VectorXd& lengths;
};

class CurveConstraintKind {
 public:
  virtual ~CurveConstraintKind() = default;
  virtual std::unique_ptr<CurveConstraint> build(const CurveEditContext& edit) const = 0;
};

using CurveConstraintRegistry = Registry<CurveConstraintKind>;
//! segment_lengths (the paper's), total_length {value} (the alternative it discusses), pin {points: edited | endpoints | [indices], at: edited |
//! reference}, tangent {points, direction: edited | reference | [x, y, z]}.
void register_curve_constraints(CurveConstraintRegistry& r);

struct CurveComponents {
  CurveEnergyRegistry energies{"curve energy"};
  CurveConstraintRegistry constraints{"curve constraint"};
  LengthSolverRegistry solvers{"length solver"};
};
const CurveComponents& curve_components();  // registered on first use

}  // namespace fairshape
