// Backend::Optimized in a fairshape built without TBB: every way of asking for it (the name
// `optimized`, the subdivision factory and one step, a hierarchy, the energy and its registry)
// throws InvalidConfig naming the cause; none falls back to the reference back end.
#include <fairshape/core/error.h>
#include <fairshape/energy/energy.h>
#include <fairshape/energy/local_quadratic.h>
#include <fairshape/subdivision/multires_surface.h>
#include <fairshape/subdivision/subdivider.h>

#include <functional>
#include <iostream>
#include <string>

#include "cube.h"

int main() {
  using namespace fairshape;
  const SurfaceMesh cube = unit_cube();
  const std::string cause = "fairshape was built without TBB (FAIRSHAPE_WITH_TBB=OFF): only the reference back end exists";
  int failures = 0;
  const auto refused = [&](const char* what, const std::function<void()>& ask) {
    try {
      ask();
      std::cout << what << ": no error\n";
      ++failures;
    } catch (const InvalidConfig& e) {
      const bool named = std::string(e.what()).find(cause) != std::string::npos;
      std::cout << what << ": " << e.what() << "\n";
      failures += !named;
    }
  };
  refused("implementation: optimized", [] { backend_from_string("optimized"); });
  refused("make_subdivider", [] { make_subdivider(Backend::Optimized); });
  refused("subdivide_once", [&] { subdivide_once(cube, SubdivisionOptions{}, Backend::Optimized); });
  refused("MultiresSurface", [&] { MultiresSurface(cube, SubdivisionOptions{}, 1, Backend::Optimized); });
  refused("stretch_bend_hessian", [&] { stretch_bend_hessian(cube, StretchBendWeights{}, Backend::Optimized); });
  refused("energy registry", [] {
    EnergyRegistry r("energy");
    register_energies(r);
    Config cfg;
    r.create("detail_preserving", Backend::Optimized, cfg);
  });
  std::cout << (failures == 0 ? "every request refused, naming the cause\n" : "FAILED\n");
  return failures == 0 ? 0 : 1;
}
