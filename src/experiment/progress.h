// Progress of a sweep: a redrawn bar on a terminal, one plain line per run otherwise (logs, CI).
#pragma once

#include <string>

#include "fairshape/core/timer.h"

namespace fairshape {

class Progress {
 public:
  Progress(int total, std::string prefix);
  //! `seconds`: the run's own time (runs.csv's time_s); the estimate of the time left is
  //! their mean times the runs left.
  void finished(int done, const std::string& run_id, const std::string& termination, double seconds);
  void close();

 private:
  int total_;
  std::string prefix_;
  bool tty_;
  double own_seconds_ = 0;  // the finished runs' time_s, summed
  Timer timer_;
};

}  // namespace fairshape
