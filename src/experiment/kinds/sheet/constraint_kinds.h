// The kinds of a sheet config's `constraints:` entries (`type:`) as one registry, like the
// energies and solvers: §4.2's point, tangent, normal, offset and region constraints, eq. 7's
// curve and §5's ribbon on a sheet, a variational curve's own curve_point and curve_tangent, and
// tangent_continuity across a joint. Each entry reads its own keys; `fairshape list` prints them.
#pragma once

#include <string>
#include <variant>

#include "fairshape/core/registry.h"
#include "fairshape/experiment/kinds/sheet/sheet_run.h"

namespace fairshape {

//! One `constraints:` entry as read: a sheet's, a variational curve's own, or a joint's
//! tangent continuity.
struct SheetConfigConstraint {
  std::variant<SheetConstraintSpec, CurveConstraintSpec, TangentContinuitySpec> spec;
};

//! What reading an entry needs from the rest of the config: its label ("constraints[2]"), the
//! sheet it defaults to and the chord tolerance its (u, v) arcs are sampled to (curve_forms.h).
struct SheetConstraintContext {
  std::string label = "constraints[]";
  std::string first_sheet = "sheet";
  double chord_tolerance = 0;
};

using SheetConstraintRegistry = Registry<SheetConfigConstraint>;

//! Every kind, its factory reading the entry's keys (all but `type`) for `context` and checking
//! that no other key is set. \throw InvalidConfig from a factory, naming the key.
SheetConstraintRegistry sheet_constraint_registry(const SheetConstraintContext& context = {});

//! Reads one entry: its `type` (one of the registry's names, default point), then its keys.
SheetConfigConstraint read_sheet_config_constraint(Config& c, const SheetConstraintContext& context);

}  // namespace fairshape
