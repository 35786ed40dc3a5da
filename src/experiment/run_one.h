// Executes one validated run: assemble, analyze, solve (timed, repeated), measure, write.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "experiment/run_spec.h"
#include "subdivision/multires_surface.h"

namespace fairshape {

// Metric columns of runs.csv, in order; every run fills every one (empty when not applicable).
const std::vector<std::string>& metric_columns();

using MetricRow = std::map<std::string, std::string>;

// Columns of steps.csv: one row per design step of a drag (problem.drag_steps), the
// yardstick's prefactored solve time beside each step's.
const std::vector<std::string>& step_columns();

// CHOLMOD's solution of a run's system and the time of its solve with the factor in hand.
struct ReferenceSolution {
  Eigen::MatrixXd u;
  double solve_s = 0;
};

// What runs of one sweep share: meshes read once, reference solutions solved once per system.
class RunCache {
 public:
  //! The hierarchy a run works on: the input mesh (0 levels), its subdivision (zero details)
  //! or its remesh (details); *build_s is the time it took to make.
  const MultiresSurface& hierarchy(const RunSpec& spec, double* build_s);
  const ReferenceSolution* reference_solution(const std::string& key) const;
  void store_reference_solution(const std::string& key, ReferenceSolution r);

 private:
  std::map<std::string, std::pair<MultiresSurface, double>> hierarchies_;
  std::map<std::string, ReferenceSolution> references_;
};

struct RunOutputs {
  std::string dir;       // the experiment's output folder
  std::string run_id;
  bool single_run = true;  // final.obj, or final/<run_id>.obj in a sweep
  //! Where the run's final geometry goes (creates final/ in a sweep).
  std::string final_path() const;
};

//! Never throws for problems of the input, the numerics or the outputs: they become the
//! row's termination and message, and the sweep goes on.
MetricRow execute_run(RunSpec& spec, RunCache& cache, const RunOutputs& out);

}  // namespace fairshape
