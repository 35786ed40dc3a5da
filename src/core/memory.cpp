#include "fairshape/core/memory.h"

#include <malloc.h>

#include <algorithm>
#include <exception>
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

// A "Name:" field (in kB) of a /proc file such as /proc/self/status or /proc/meminfo, in MiB;
// -1 when absent.
double proc_field_mb(const char* path, const std::string& field) {
  std::ifstream f(path);
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

double status_mb(const std::string& field) { return proc_field_mb("/proc/self/status", field); }
double meminfo_mb(const std::string& field) { return proc_field_mb("/proc/meminfo", field); }

// The cgroup v2 limit's headroom (memory.max − memory.current) in MiB; -1 without a limit.
double cgroup_headroom_mb() {
  std::ifstream max_file("/sys/fs/cgroup/memory.max"), current_file("/sys/fs/cgroup/memory.current");
  std::string max;
  double current = 0;
  if (!(max_file >> max) || max == "max" || !(current_file >> current)) return -1.0;
  try {
    return (std::stod(max) - current) / (1024.0 * 1024.0);
  } catch (const std::exception&) {
    return -1.0;
  }
}

}  // namespace

double peak_rss_mb() { return status_mb("VmHWM:"); }

double available_memory_mb() {
  const double available = meminfo_mb("MemAvailable:"), swap = meminfo_mb("SwapFree:");
  double out = available < 0 ? -1.0 : available + std::max(swap, 0.0);
  if (const double cgroup = cgroup_headroom_mb(); cgroup >= 0) out = out < 0 ? cgroup : std::min(out, cgroup);
  return out;
}

void release_free_memory() { malloc_trim(0); }

double trimmed_rss_mb() {
  release_free_memory();
  return status_mb("VmRSS:");
}

}  // namespace fairshape
