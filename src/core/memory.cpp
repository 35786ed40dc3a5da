#include "fairshape/core/memory.h"

#include <malloc.h>

#include <fstream>
#include <string>

namespace fairshape {

bool reset_peak_rss() {
  std::ofstream f("/proc/self/clear_refs");
  if (!f) return false;
  f << "5";  // "5" resets the peak RSS counter, see proc(5)
  return static_cast<bool>(f.flush());
}

namespace {

// A "Vm...:" field of /proc/self/status in MiB; -1 when absent.
double status_mb(const std::string& field) {
  std::ifstream f("/proc/self/status");
  std::string key;
  while (f >> key) {
    if (key == field) {
      double kib = 0;
      f >> kib;
      return kib / 1024.0;
    }
    std::getline(f, key);
  }
  return -1.0;
}

}  // namespace

double peak_rss_mb() { return status_mb("VmHWM:"); }

void release_free_memory() { malloc_trim(0); }

double trimmed_rss_mb() {
  release_free_memory();
  return status_mb("VmRSS:");
}

}  // namespace fairshape
