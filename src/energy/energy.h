// A quadratic fairness energy E(u) = ½ Σ_c u_cᵀ H u_c over the vertices of a mesh, one
// shared N×N matrix H for the x, y and z columns of u (positions or displacements).
#pragma once

#include <memory>
#include <string>

#include "fairshape/core/registry.h"
#include "fairshape/core/types.h"
#include "fairshape/mesh/surface_mesh.h"

namespace fairshape {

class LocalRotations;

class Energy {
 public:
  virtual ~Energy() = default;
  //! Adds weight × H to `out`, as triplets over vertex ids of `rest`.
  virtual void add_hessian(const SurfaceMesh& rest, double weight, Triplets& out) const = 0;
  //! weight × H as a matrix; energies with a faster route than triplets override it.
  virtual SparseMatrix hessian(const SurfaceMesh& rest, double weight) const {
    Triplets t;
    add_hessian(rest, weight, t);
    SparseMatrix H(rest.n_vertices(), rest.n_vertices());
    H.setFromTriplets(t.begin(), t.end());
    return H;
  }
  //! True when the energy is of the deformed positions P_rest + u rather than of the
  //! displacement u: the problem then gains the linear term −H P_rest.
  virtual bool measures_positions() const { return false; }
  //! \throw InvalidInput when the energy cannot be assembled on `rest` (too high a valence,
  //! say): the check alone, cheap, so a sweep can make it for every run before the first.
  virtual void check_applicable(const SurfaceMesh& rest) const { (void)rest; }
  //! An energy of the deformation made of per-vertex derivatives (detail_preserving) offers the
  //! local step of a rotation-aware solve (energy/local_rotations.h); nullptr where it has none.
  virtual std::unique_ptr<LocalRotations> local_rotations(const SurfaceMesh& rest, double weight) const;
};

using EnergyRegistry = Registry<Energy>;
void register_energies(EnergyRegistry& r);

}  // namespace fairshape
