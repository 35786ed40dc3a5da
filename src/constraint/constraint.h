// Constraints that prescribe the value of some vertices' unknowns (u_i = target_i).
// Later constraint kinds (normals, curves, lengths) add linear rows or nonlinear terms.
#pragma once

#include <map>
#include <memory>

#include "core/registry.h"
#include "core/types.h"
#include "mesh/surface_mesh.h"

namespace fairshape {

// Prescribed displacements per vertex; setting one vertex twice to different values throws.
class PrescribedValues {
 public:
  void set(int vertex, const Vec3& value, const std::string& who);
  const std::map<int, Vec3>& values() const { return values_; }

 private:
  std::map<int, Vec3> values_;
  std::map<int, std::string> owner_;
};

class Constraint {
 public:
  virtual ~Constraint() = default;
  //! Adds this constraint's prescribed displacements (u = x − x_rest) on `rest`.
  virtual void prescribe(const SurfaceMesh& rest, PrescribedValues& out) const = 0;
};

using ConstraintRegistry = Registry<Constraint>;
void register_constraints(ConstraintRegistry& r);

}  // namespace fairshape
