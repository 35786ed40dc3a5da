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

#include "fairshape/core/registry.h"
#include "fairshape/core/types.h"
#include "fairshape/mesh/surface_mesh.h"
#include "fairshape/subdivision/limit_evaluation.h"

namespace fairshape {

// A point of a level's limit surface (face and parameters there) as stencils over that
// level's vertices (subdivision/limit_evaluation.h); `position` empty: not a surface point.
struct SurfacePoint {
  FaceParameter at;
  std::vector<int> corners;  // the face's vertices (ids persist on finer levels: for marking)
  Stencil position, du, dv;
  bool empty() const { return position.empty(); }
};

struct PointConstraint {
  int level = 0;          // where the constrained vertex lives
  int vertex = 0;
  bool on_limit = false;  // constrain the vertex's limit position instead
  Vec3 offset = Vec3::Zero();
  std::string label;      // names the constraint in error messages
  SurfacePoint surface = {};  // non-empty: the limit point there moves by `offset` (vertex, on_limit unused)
};

// How a normal constraint's rows impose it (papers/boier-martin/README.md, "Folds and reversed
// normals"). §4.2's two rows make the tangents perpendicular to N, which −N satisfies as well;
// the frame rows prescribe the tangents themselves, turned with the normal, so only N does.
enum class NormalRows {
  Auto,     // tangent; an edit whose answer meets N by its reverse is solved again with frame
  Tangent,  // §4.2: Q_u · N = Q_v · N = 0 (two rows coupling x, y and z)
  Frame,    // Q_u = R Q_u⁰, Q_v = R Q_v⁰, R the shortest rotation of the rest normal onto N
};

// The normal at `vertex` should be `normal` (unit): the quadratic fit's tangents Q_u, Q_v
// (divided differences of the rest shape) are made perpendicular to it — two linear rows that
// couple x, y and z — or, with frame rows, equal to the rest ones turned onto it.
struct NormalConstraint {
  int level = 0;
  int vertex = 0;
  Vec3 normal = Vec3::UnitZ();
  std::string label;
  SurfacePoint surface = {};  // non-empty: the rows are N·∂S/∂u = N·∂S/∂v = 0 there instead
  NormalRows rows = NormalRows::Auto;
};

// A curve constraint's chain of snapped vertices, in order along the curve (for drawing it).
struct PlacedCurve {
  int level = 0;
  std::vector<int> vertices;
  bool closed = false;
  std::string label;
  std::vector<SurfacePoint> samples = {};  // placement limit_points: the curve's points on the limit surface
  std::string note = {};  // how it was placed when that differs from what was asked (a run's message says it)
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
  //! As add_to, knowing the subdivision rules: constraints at points of the limit surface
  //! need them; the others ignore them.
  virtual void add_on_surface(const LevelMeshes& mesh_at, int finest_level, const SubdivisionOptions& /*rules*/,
                              DesignConstraints& out) const {
    add_to(mesh_at, finest_level, out);
  }
};

//! The vertices a placed point constraint marks in result meshes: its vertex, or the corners
//! of the face its surface point lies on.
inline std::vector<int> marked_vertices(const PointConstraint& c) {
  return c.surface.empty() ? std::vector<int>{c.vertex} : c.surface.corners;
}

//! The level a config's `level` key names (-1: the finest). \throw InvalidInput when absent.
int resolve_level(int level, int finest, const std::string& who);

using ConstraintRegistry = Registry<Constraint>;
void register_constraints(ConstraintRegistry& r);

}  // namespace fairshape
