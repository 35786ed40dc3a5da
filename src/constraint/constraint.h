// Constraints as the designer places them: point constraints (a vertex's displacement, or
// its limit position's) on some level of a multiresolution surface. The design module
// propagates them to the edit level (Boier-Martin et al. §4.2); a plain mesh is a hierarchy
// with one level. Later kinds (normals, curves, lengths) add rows or nonlinear terms.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/registry.h"
#include "core/types.h"
#include "mesh/surface_mesh.h"

namespace fairshape {

struct PointConstraint {
  int level = 0;          // where the constrained vertex lives
  int vertex = 0;
  bool on_limit = false;  // constrain the vertex's limit position instead
  Vec3 offset = Vec3::Zero();
  std::string label;      // names the constraint in error messages
};

//! The meshes of a hierarchy, by level (0 = base .. finest).
using LevelMeshes = std::function<const SurfaceMesh&(int level)>;

class Constraint {
 public:
  virtual ~Constraint() = default;
  //! Appends this constraint's point constraints. \throw InvalidInput (missing level or vertex,
  //! empty selection).
  virtual void add_points(const LevelMeshes& mesh_at, int finest_level, std::vector<PointConstraint>& out) const = 0;
};

using ConstraintRegistry = Registry<Constraint>;
void register_constraints(ConstraintRegistry& r);

}  // namespace fairshape
