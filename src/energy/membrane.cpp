// Membrane (stretch) energy ½ Σ_edges w_ij |u_i − u_j|²: its Hessian is −L.
#include "fairshape/energy/energy.h"
#include "fairshape/energy/laplacian.h"

namespace fairshape {
namespace {

class Membrane : public Energy {
 public:
  explicit Membrane(LaplacianWeights w) : weights_(w) {}
  void add_hessian(const SurfaceMesh& rest, double weight, Triplets& out) const override {
    const SparseMatrix L = graph_laplacian(rest, weights_);
    for (int k = 0; k < L.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(L, k); it; ++it)
        out.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), -weight * it.value());
  }

 private:
  LaplacianWeights weights_;
};

}  // namespace

std::unique_ptr<Energy> make_membrane(Config& cfg) {
  static const NameTable<LaplacianWeights> names{{LaplacianWeights::Uniform, "uniform"},
                                                 {LaplacianWeights::Cotangent, "cotangent"}};
  return std::make_unique<Membrane>(
      cfg.get_enum("weights", LaplacianWeights::Uniform, names, "edge weights of the Laplacian"));
}

}  // namespace fairshape
