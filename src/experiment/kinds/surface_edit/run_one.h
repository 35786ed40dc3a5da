// Executes one validated run: assemble, analyze, solve (timed, repeated), measure, write.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "fairshape/experiment/run_outputs.h"
#include "fairshape/experiment/kinds/surface_edit/drag_run.h"
#include "fairshape/experiment/kinds/surface_edit/surface_edit_spec.h"
#include "fairshape/remesh/remesh.h"
#include "fairshape/subdivision/multires_surface.h"

namespace fairshape {

// Metric columns of runs.csv, in order; every run fills every one (empty when not applicable).
const std::vector<std::string>& metric_columns();

// Columns of steps.csv: one row per design step of a drag (problem.drag_steps), the
// yardstick's prefactored solve time beside each step's.
const std::vector<std::string>& step_columns();
// Columns of iterations.csv: one row per residual check of the solve (output.iterations).
const std::vector<std::string>& iteration_columns();


// Work that runs of one process share — a hierarchy built or loaded, a reference solution —
// is done once and charged to no run: its time is left out of the time_s of the run during
// which it happened and goes to setup.csv instead (configs/README.md, "Timing columns"), so a
// run's timings never depend on which run came first or which worker took it.
struct SharedSetup {
  std::string id;    // stable for the same work in every process: "hierarchy-<hash>", "reference-<hash>"
  std::string what;  // what was built, for a reader of setup.csv
  double seconds = 0;
};

// setup.csv's columns (after the key columns of the run during which the work was done).
const std::vector<std::string>& setup_columns();

// What runs of one sweep share: meshes read once, reference solutions solved once per system.
class RunCache {
 public:
  //! The hierarchy a run works on: the input mesh (0 levels), its subdivision (zero details)
  //! or its remesh (details); *made (if given) the remesh's quality report, or null when the
  //! hierarchy was not remeshed here. Building it records a SharedSetup.
  const MultiresSurface& hierarchy(const SurfaceEditSpec& spec, const RemeshReport** made = nullptr);
  const ReferenceSolution* reference_solution(const std::string& key);
  //! Stores a reference solution and records its solve (factorization included) as shared work.
  void store_reference_solution(const std::string& key, ReferenceSolution r, double seconds, std::string what);
  //! The shared work done since the last call (oldest first) and the ids of all shared work
  //! asked for since then, built or found: a run takes them when it ends.
  struct Setups {
    std::vector<SharedSetup> built;
    std::vector<std::string> used;
  };
  Setups take_setups();

 private:
  std::map<std::string, MultiresSurface> hierarchies_;
  std::map<std::string, std::string> hierarchy_ids_;  // by the key of hierarchies_
  std::map<std::string, RemeshReport> remesh_reports_;
  std::map<std::string, ReferenceSolution> references_;
  void use(const std::string& id);
  Setups setups_;
};

//! Never throws for problems of the input, the numerics or the outputs: they become the
//! row's termination and message, and the sweep goes on.
MetricRow execute_run(SurfaceEditSpec& spec, RunCache& cache, const RunOutputs& out);

}  // namespace fairshape
