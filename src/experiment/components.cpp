#include "fairshape/experiment/components.h"

namespace fairshape {

void register_all(Components& c) {
  register_energies(c.energies);
  register_constraints(c.constraints);
  register_solvers(c.solvers);
  reference::register_solvers(c.solvers);
}

const Components& components() {
  static const Components instance = [] {
    Components c;
    register_all(c);
    return c;
  }();
  return instance;
}

}  // namespace fairshape
