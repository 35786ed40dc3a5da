#include "fairshape/energy/energy.h"

namespace fairshape {

std::unique_ptr<Energy> make_membrane(Config& cfg);
std::unique_ptr<Energy> make_thin_plate(Config& cfg);
void register_stretch_bend(EnergyRegistry& r);

void register_energies(EnergyRegistry& r) {
  // Assembly is cheap and serial for these; both back ends share one implementation.
  for (Backend b : built_backends()) {
    r.add("membrane", b, "stretch energy: ½ Σ_edges w_ij |u_i − u_j|² (Hessian −L)", make_membrane);
    r.add("umbrella_thin_plate", b, "bending energy: ½ Σ_i |umbrella(u)_i|² (Hessian UᵀU)", make_thin_plate);
  }
  r.add_former_name("thin_plate", "umbrella_thin_plate");  // until this release
  register_stretch_bend(r);
}

}  // namespace fairshape
