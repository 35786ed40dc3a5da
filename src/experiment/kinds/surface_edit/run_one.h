// Executes one validated run: assemble, analyze, solve (timed, repeated), measure, write.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "fairshape/experiment/run_outputs.h"
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

// CHOLMOD's solution of a run's system and the time of its solve with the factor in hand.
struct ReferenceSolution {
  Eigen::MatrixXd u;
  double solve_s = 0;
};

// What runs of one sweep share: meshes read once, reference solutions solved once per system.
class RunCache {
 public:
  //! The hierarchy a run works on: the input mesh (0 levels), its subdivision (zero details)
  //! or its remesh (details); *build_s is the time it took to make, *made (if given) the
  //! remesh's quality report, or null when the hierarchy was not remeshed here.
  const MultiresSurface& hierarchy(const SurfaceEditSpec& spec, double* build_s,
                                   const RemeshReport** made = nullptr);
  const ReferenceSolution* reference_solution(const std::string& key) const;
  void store_reference_solution(const std::string& key, ReferenceSolution r);

 private:
  std::map<std::string, std::pair<MultiresSurface, double>> hierarchies_;
  std::map<std::string, RemeshReport> remesh_reports_;
  std::map<std::string, ReferenceSolution> references_;
};

//! Never throws for problems of the input, the numerics or the outputs: they become the
//! row's termination and message, and the sweep goes on.
MetricRow execute_run(SurfaceEditSpec& spec, RunCache& cache, const RunOutputs& out);

}  // namespace fairshape
