// Point and normal constraints at arbitrary points of the limit surface, as written in a
// `position`, `fixed` or `normal` constraint's config instead of a vertex selection:
//   at: {face: 12, uv: [0.3, 0.7], level: -1}   a face of one level (-1: the finest; default:
//                                                 the constraint's `level`) and its parameters
//   nearest_on_limit: [x, y, z]                  the closest point of that level's limit surface
// Each becomes one SurfacePoint (constraint.h): the limit point's stencil over the level's
// vertices (subdivision/limit_evaluation.h), propagated to the edit level like a vertex.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "fairshape/constraint/constraint.h"
#include "fairshape/core/config.h"

namespace fairshape {

class SurfacePointSelection {
 public:
  //! The selection a config gives, or nullopt when it has neither key. Reads `at` and
  //! `nearest_on_limit` (so documentation lists them). \throw InvalidConfig for malformed
  //! values, both keys, or one of them together with a vertex selection key.
  static std::optional<SurfacePointSelection> from_config(Config& cfg, int level);
  static SurfacePointSelection at(int level, const FaceParameter& p);
  static SurfacePointSelection nearest(int level, const Vec3& p);

  //! The level (resolved) and the surface point there. \throw InvalidInput naming the key
  //! (`key_`) and the valid range: a face that does not exist or is not a quad (Catmull-Clark)
  //! or triangle (Loop), a (u, v) outside the face.
  //! True for `at` (a face given), false for `nearest_on_limit` (a face found).
  bool face_given() const { return at_.has_value(); }
  std::pair<int, SurfacePoint> resolve(const LevelMeshes& mesh_at, int finest, const SubdivisionOptions& rules,
                                       const std::string& who) const;

 private:
  int level_ = -1;
  std::optional<FaceParameter> at_;
  Vec3 nearest_ = Vec3::Zero();
  std::string key_ = "at";  // the config key named in errors
};

//! Stencils and corners of the limit point at `p` (already checked by the evaluator).
SurfacePoint make_surface_point(const LimitEvaluator& evaluator, const FaceParameter& p);

//! `position`/`fixed` at a surface point: its limit point moves by `offset`.
std::unique_ptr<Constraint> surface_point_offset(SurfacePointSelection where, const Vec3& offset, std::string who);
//! `normal` at a surface point: the limit normal there becomes `normal`.
std::unique_ptr<Constraint> surface_point_normal(SurfacePointSelection where, const Vec3& normal, NormalRows rows,
                                                 std::string who);

}  // namespace fairshape
