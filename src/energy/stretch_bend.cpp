// The two registered formulations of the stretch + bend energy (Boier-Martin et al.):
//   thin-plate         energy of the deformed positions, E(P_rest + ΔP) (§3.4);
//   detail-preserving  energy of the deformation itself, E(ΔP), with the divided differences
//                      taken from the rest shape (§4.1): details ride along with an edit.
// The unknowns are always displacements; thin-plate's linear term −H P_rest comes from
// measures_positions().
#include "fairshape/energy/energy.h"
#include "fairshape/energy/local_quadratic.h"
#include "fairshape/energy/local_rotations.h"
#include "fairshape/energy/ring_coupling.h"

namespace fairshape {
namespace {

class StretchBend : public Energy {
 public:
  StretchBend(StretchBendWeights w, Backend backend, bool positions)
      : w_(w), backend_(backend), positions_(positions) {}
  void add_hessian(const SurfaceMesh& rest, double weight, Triplets& out) const override {
    add_stretch_bend_hessian(rest, w_, weight, out, backend_);
  }
  SparseMatrix hessian(const SurfaceMesh& rest, double weight) const override {
    return stretch_bend_hessian(rest, w_, weight, backend_);
  }
  bool measures_positions() const override { return positions_; }
  void check_applicable(const SurfaceMesh& rest) const override { check_ring_coupling(rest, "stretch + bend energy"); }
  std::unique_ptr<LocalRotations> local_rotations(const SurfaceMesh& rest, double weight) const override {
    if (positions_) return nullptr;  // the thin plate of the surface has no rest derivatives to turn
    return std::make_unique<LocalRotations>(rest, w_, weight);
  }

 private:
  StretchBendWeights w_;
  Backend backend_;
  bool positions_;
};

StretchBendWeights weights_from(Config& cfg) {
  StretchBendWeights w;
  w.alpha = cfg.get_number("alpha", w.alpha, 0.0, 1e12, "stretch weight α (first divided differences)");
  w.beta = cfg.get_number("beta", w.beta, 0.0, 1e12, "bend weight β (second divided differences)");
  if (w.alpha == 0 && w.beta == 0) throw InvalidConfig(cfg.path() + ": alpha and beta are both zero");
  return w;
}

}  // namespace

std::unique_ptr<LocalRotations> Energy::local_rotations(const SurfaceMesh&, double) const { return nullptr; }

std::unique_ptr<Energy> make_stretch_bend(StretchBendWeights w, StretchBendOf of, Backend backend) {
  if (!(w.alpha >= 0) || !(w.beta >= 0) || (w.alpha == 0 && w.beta == 0))
    throw InvalidInput("stretch + bend energy: alpha and beta must be >= 0 and not both zero");
  require_backend(backend);
  return std::make_unique<StretchBend>(w, backend, of == StretchBendOf::Positions);
}

void register_stretch_bend(EnergyRegistry& r) {
  for (Backend b : built_backends()) {
    r.add("surface_thin_plate", b,
          "α·stretch + β·bend of the deformed surface, local quadratic fits (Boier-Martin et al. §3.4)",
          [b](Config& cfg) { return make_stretch_bend(weights_from(cfg), StretchBendOf::Positions, b); });
    r.add("detail_preserving", b,
          "α·stretch + β·bend of the deformation ΔP, fits from the rest shape (Boier-Martin et al. §4.1)",
          [b](Config& cfg) { return make_stretch_bend(weights_from(cfg), StretchBendOf::Deformation, b); });
  }
  // Their names until this release: `thin-plate` was one punctuation mark from the umbrella
  // energy's `thin_plate`, a different energy.
  r.add_former_name("thin-plate", "surface_thin_plate");
  r.add_former_name("detail-preserving", "detail_preserving");
}

}  // namespace fairshape
