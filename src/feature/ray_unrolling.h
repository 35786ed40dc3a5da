// Walking straight on a triangulated surface (Khodakovsky & Schröder, "Fine level feature
// editing for subdivision surfaces", §2.1.2): a ray is projected into the plane of the face it
// is in; where it leaves the face across an edge it is projected twice, first into the tangent
// plane at the edge point (normal interpolated from the edge's end points), then into the plane
// of the next face; where it runs into a vertex the vertex's one-ring is projected to the
// vertex's tangent plane and the ray crosses the ring there. Lengths are measured as unrolled.
#pragma once

#include <vector>

#include "fairshape/core/error.h"
#include "fairshape/feature/triangle_surface.h"

namespace fairshape::feature {

//! A one-ring that does not project one-to-one onto its vertex's tangent plane: the surface is
//! not flat at the scale of the feature (the paper's standing assumption).
class FlatnessError : public InvalidInput {
 public:
  FlatnessError(int vertex, const std::string& what) : InvalidInput(what), vertex_(vertex) {}
  int vertex() const { return vertex_; }

 private:
  int vertex_;
};

struct UnrolledRay {
  SurfacePoint end;
  Vec3 end_direction = Vec3::Zero();  // unit, in the end face's plane
  std::vector<Vec3> path;             // start, every crossing, end
  std::vector<double> arc;            // unrolled length at each path point
  bool hit_boundary = false;          // stopped early at the surface's boundary
  double length() const { return arc.empty() ? 0.0 : arc.back(); }
};

//! Unrolls the ray from `start` in `direction` (projected into the start face) over `length`.
//! \throw FlatnessError for a vertex ring that does not project one-to-one.
UnrolledRay unroll_ray(const TriangleSurface& s, const SurfacePoint& start, const Vec3& direction, double length);

//! A straight piece inside one face, end points as barycentric coordinates of that face.
struct FacePiece {
  int face = -1;
  Vec3 from = Vec3::Zero(), to = Vec3::Zero();
};

//! The straightest walk from `from` towards `to`, split wherever it crosses an edge (Figure 5).
//! \throw InvalidInput when the walk leaves the surface across its boundary or does not arrive.
std::vector<FacePiece> walk_between(const TriangleSurface& s, const SurfacePoint& from, const SurfacePoint& to);

}  // namespace fairshape::feature
