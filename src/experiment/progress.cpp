#include "fairshape/experiment/progress.h"

#include <unistd.h>

#include <cstdio>

namespace fairshape {

Progress::Progress(int total, std::string prefix)
    : total_(total), prefix_(std::move(prefix)), tty_(::isatty(STDERR_FILENO) != 0) {}

void Progress::finished(int done, const std::string& run_id, const std::string& termination, double seconds) {
  const double elapsed = timer_.seconds();
  // From the runs' own times (time_s), not the elapsed time: work shared between runs (a
  // hierarchy built once) happens once and is not expected again for every run left.
  own_seconds_ += seconds;
  const double eta = done > 0 ? own_seconds_ / done * (total_ - done) : 0.0;
  if (tty_) {
    const int width = 30, filled = total_ > 0 ? width * done / total_ : width;
    std::fprintf(stderr, "\r%s[%.*s%*s] %d/%d  elapsed %.0fs  eta %.0fs  last: %s (%.2fs)   ", prefix_.c_str(),
                 filled, "==============================", width - filled, "", done, total_, elapsed, eta,
                 termination.c_str(), seconds);
  } else {
    std::fprintf(stderr, "%srun %d/%d %s: %s in %.3fs (eta %.0fs)\n", prefix_.c_str(), done, total_, run_id.c_str(),
                 termination.c_str(), seconds, eta);
  }
  std::fflush(stderr);
}

void Progress::close() {
  if (tty_) std::fprintf(stderr, "\n");
}

}  // namespace fairshape
