// Timing repeats, owned by the harness for every run kind: a run is executed `repeat` times,
// the first into the output folder, the others into a scratch folder that is removed; every
// measured column (timings, memory) reports the median over the executions, an `X_min_s`
// column beside an `X_s` one the minimum, and the other columns — the results — must agree
// across executions, or the message names those that did not (a non-deterministic run).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "fairshape/experiment/run_outputs.h"

namespace fairshape {

//! `execute` runs once into the outputs it is given. `succeeded` tells a successful row.
MetricRow run_repeated(int repeat, const std::vector<std::string>& measured_columns, const RunOutputs& out,
                       const std::function<MetricRow(const RunOutputs&)>& execute,
                       const std::function<bool(const MetricRow&)>& succeeded);

//! The default measured columns of a kind: those ending in `_s` (seconds) or `_mb` (memory).
std::vector<std::string> measured_by_name(const std::vector<std::string>& metric_columns);

}  // namespace fairshape
