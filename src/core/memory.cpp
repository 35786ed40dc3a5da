#include "core/memory.h"

#include <fstream>
#include <string>

namespace fairshape {

bool reset_peak_rss() {
  std::ofstream f("/proc/self/clear_refs");
  if (!f) return false;
  f << "5";  // "5" resets the peak RSS counter, see proc(5)
  return static_cast<bool>(f.flush());
}

double peak_rss_mb() {
  std::ifstream f("/proc/self/status");
  std::string key;
  while (f >> key) {
    if (key == "VmHWM:") {
      double kib = 0;
      f >> kib;
      return kib / 1024.0;
    }
    std::getline(f, key);
  }
  return -1.0;
}

}  // namespace fairshape
