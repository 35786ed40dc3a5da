// How numbers are written into the CSV files of a run: 10 significant digits.
#pragma once

#include <sstream>
#include <string>

namespace fairshape {

inline std::string num(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

}  // namespace fairshape
