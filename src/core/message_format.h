// How numbers are written into messages (solver reports, warnings, errors): scientific
// notation with 3 significant digits, so a tolerance of 1e-8 never prints as "0.000000" (what
// std::to_string makes of it).
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

}  // namespace fairshape
