// `fairshape submit CONFIG --slurm`: a sweep written (and with --now submitted) as a Slurm job
// array of shards plus a merge job (src/experiment/slurm_array.h). Kept apart from CLI11.
#pragma once

#include <string>
#include <vector>

#include "fairshape/experiment/slurm_array.h"

namespace fairshape::cli {

struct SubmitArgs {
  std::string config, out;
  bool slurm = false, now = false, smoke = false;
  std::string array_size;  // empty: min(points, kDefaultArraySize); checked by cmd_submit
  std::vector<std::string> sets;
  std::vector<std::string> setup;  // --setup lines
  SlurmResources resources;
};

//! Tasks of an array when --array-size is not given (fewer if the sweep has fewer points).
constexpr int kDefaultArraySize = 16;

//! \return 0; \throw InvalidConfig (exit 2) for bad options, a missing sbatch with --now, an
//! invalid sweep point, an --out that holds files.
int cmd_submit(const SubmitArgs& a);

}  // namespace fairshape::cli
