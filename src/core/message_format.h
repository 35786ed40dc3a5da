// How numbers are written into messages (solver reports, warnings, errors): scientific
// notation with 3 significant digits, so a tolerance of 1e-8 never prints as "0.000000" (what
// std::to_string makes of it); measured values as the CSV files of a run write them.
#pragma once

#include <sstream>
#include <string>

namespace fairshape {

inline std::string sci(double v) {
  std::ostringstream os;
  os.precision(2);
  os << std::scientific << v;
  return os.str();
}

//! 10 significant digits: a run's CSV cells (experiment/metric_format.h) and the messages that
//! quote the same measurements.
inline std::string num(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

}  // namespace fairshape
