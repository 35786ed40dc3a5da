// Constraints as the designer places them on some level of a multiresolution surface
// (Boier-Martin et al. §4.2): point constraints (a vertex's displacement, or its limit
// position's) and normal constraints (the surface normal at a vertex). Curves become point
// constraints at the vertices along them. The design module propagates everything to the
// edit level; a plain mesh is a hierarchy with one level.
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

// The normal at `vertex` should be `normal` (unit): the quadratic fit's tangents Q_u, Q_v
// (divided differences of the rest shape) are made perpendicular to it — two linear rows that
// couple x, y and z.
struct NormalConstraint {
  int level = 0;
  int vertex = 0;
  Vec3 normal = Vec3::UnitZ();
  std::string label;
};

// A curve constraint's chain of snapped vertices, in order along the curve (for drawing it).
struct PlacedCurve {
  int level = 0;
  std::vector<int> vertices;
  bool closed = false;
  std::string label;
};

struct DesignConstraints {
  std::vector<PointConstraint> points;
  std::vector<NormalConstraint> normals;
  std::vector<PlacedCurve> curves;  // their vertices are also in `points`
};

//! The meshes of a hierarchy, by level (0 = base .. finest).
using LevelMeshes = std::function<const SurfaceMesh&(int level)>;

class Constraint {
 public:
  virtual ~Constraint() = default;
  //! Appends this constraint's point and normal constraints. \throw InvalidInput (missing
  //! level or vertex, empty selection, a curve off the surface).
  virtual void add_to(const LevelMeshes& mesh_at, int finest_level, DesignConstraints& out) const = 0;
};

//! The level a config's `level` key names (-1: the finest). \throw InvalidInput when absent.
int resolve_level(int level, int finest, const std::string& who);

using ConstraintRegistry = Registry<Constraint>;
void register_constraints(ConstraintRegistry& r);

}  // namespace fairshape
