// Discrete thin-plate (bending) energy ½ Σ_i |(U u)_i|² with U the umbrella operator:
// its Hessian is UᵀU, which annihilates translations.
#include "fairshape/energy/energy.h"
#include "fairshape/energy/laplacian.h"
#include "fairshape/energy/ring_coupling.h"

namespace fairshape {
namespace {

class ThinPlate : public Energy {
 public:
  void check_applicable(const SurfaceMesh& rest) const override {
    check_ring_coupling(rest, "umbrella thin-plate energy");
  }
  void add_hessian(const SurfaceMesh& rest, double weight, Triplets& out) const override {
    check_applicable(rest);
    const SparseMatrix U = umbrella_operator(rest);
    const SparseMatrix H = SparseMatrix(U.transpose()) * U;
    for (int k = 0; k < H.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(H, k); it; ++it)
        out.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), weight * it.value());
  }
};

}  // namespace

std::unique_ptr<Energy> make_thin_plate(Config&) { return std::make_unique<ThinPlate>(); }

}  // namespace fairshape
