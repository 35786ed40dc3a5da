// A run's `threads:` key as a TBB limit for the duration of the run (0: the machine's).
#pragma once

#include <tbb/global_control.h>

#include <memory>

namespace fairshape {

inline std::unique_ptr<tbb::global_control> limit_threads(int threads) {
  if (threads <= 0) return nullptr;
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
}

}  // namespace fairshape
