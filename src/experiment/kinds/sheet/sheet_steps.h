// A sheet config's design steps as SheetSession steps (bspline/sheet_session.h): the session
// made from the spec, and at each step the edits its schedule asks — constraints switched on
// (`step`) and off (`until`), targets dragged (`moves`), space curves edited, traced or held on
// the current sheet, rest shapes installed or melted (§5) — with the variational curves solved
// with the sheets joined to them (free_curves.h). The run kind turns each step into rows and
// files; the Python binding drives the same object, so a config and a Python session of the same
// steps give the same sheets.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "fairshape/bspline/sheet_session.h"
#include "fairshape/experiment/kinds/sheet/free_curves.h"
#include "fairshape/experiment/kinds/sheet/sheet_run.h"
#include "fairshape/io/constraint_overlay.h"

namespace fairshape {

//! What one scheduled step did: the session's step, the variational curves' rows, the space
//! curves as they are now, and what a figure draws over it.
struct SheetConfigStep {
  int step = 0;
  SheetStep result;
  std::vector<FreeCurveStep> free_curves;
  std::map<std::string, std::vector<Vec3>> curves_now;
  ConstraintOverlay overlay;
};

class SheetConfigSteps {
 public:
  //! The sheets (refined up front as the spec asks) and the spec's solver, moved into the
  //! session; the curves traced on the initial sheets. \throw InvalidInput for a variational
  //! curve that cannot be fitted.
  explicit SheetConfigSteps(SheetRunSpec spec);

  const SheetRunSpec& spec() const { return spec_; }
  int steps() const { return spec_.steps(); }
  int next_step() const { return next_; }
  //! Applies the next scheduled step and solves. \throw InvalidInput when none is left.
  SheetConfigStep advance();
  SheetSession& session() { return session_; }
  const SheetSession& session() const { return session_; }

  //! A constraint on a sheet from one `constraints:` entry (the config's reader and checks,
  //! constraint_kinds.h), resolved as the schedule would at the current step: relative
  //! targets from the initial sheet, held surfaces the current one. Its step, until and moves
  //! must not be given: the caller decides when it comes and goes. \throw InvalidConfig naming the key.
  SessionConstraint read_constraint(const YAML::Node& entry);

 private:
  SheetEdits edits_at(int step);
  SessionConstraint resolved(const SheetConstraintSpec& cs, int step) const;
  JointSolve joint_solve(int step, SheetConfigStep& out);

  SheetRunSpec spec_;
  SheetSession session_;
  int next_ = 0;
  std::map<std::string, std::vector<Vec3>> base_curves_;  // each curve before its edits
  std::map<std::string, std::vector<Vec3>> curves_now_;   // ... and at the current step
  // Curves traced on the current surface at their first step, and the surfaces regions and
  // ribbons hold (by constraint label): the targets they keep.
  std::map<std::string, std::shared_ptr<const bspline::SurfaceTrace>> traced_on_, held_;
  std::unique_ptr<FreeCurves> free_curves_;
};

//! The space curve `c` at `step`: its base polyline moved by the edits up to then (cosine bumps in t).
std::vector<Vec3> curve_at_step(const SpaceCurveSpec& c, const std::vector<Vec3>& base, int step);

}  // namespace fairshape
