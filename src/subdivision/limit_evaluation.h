// Exact evaluation of a subdivision surface's limit at any parameter value of any face of a
// control mesh, as stencils: the limit point S(f; u, v) and its derivatives ∂S/∂u, ∂S/∂v are
// linear combinations Σ_j w_j X_j of the mesh's vertices X_j. Constraints at arbitrary surface
// points ("Detail-preserving variational surface design with multiresolution constraints",
// §4.2, curves as sequences of points) are then linear rows exactly like vertex constraints.
//
// Backed by OpenSubdiv's Bfr (base-face representation of the limit surface, Debian's
// libosd-dev): regular faces are exact bicubic B-spline (Catmull-Clark) or quartic box-spline
// (Loop) patches; faces next to an extraordinary vertex are refined adaptively kApproxLevel
// times around it and closed with Gregory patches, which interpolate the exact limit position
// and tangents at the vertex (the remaining deviation lives in a region 2^-kApproxLevel of the
// face wide). papers/boier-martin/README.md, "Constraints at surface points", has the
// measurements.
//
// Parameterization of a face (its vertices in the mesh's order): a quad (Catmull-Clark) is
// [0, 1]², vertices at (0,0), (1,0), (1,1), (0,1); a triangle (Loop) is u, v ≥ 0, u + v ≤ 1,
// vertices at (0,0), (1,0), (0,1). A Catmull-Clark face that is not a quad (an N-gon of a
// base mesh) is refused with a message that names the same point one level finer, where the
// N-gon is N quads (each with the parameterization above, from its corner of the N-gon to
// the N-gon's centroid): that is how OpenSubdiv parameterizes N-gons too (its quad sub-faces),
// and every level from 1 on is all quads, so the finer address is the unambiguous one.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "fairshape/mesh/surface_mesh.h"
#include "fairshape/subdivision/scheme.h"

namespace fairshape {

//! Weights over a mesh's vertices: (vertex id, weight).
using Stencil = std::vector<std::pair<int, double>>;

//! A point given by a face of a mesh and its parameters there.
struct FaceParameter {
  int face = -1;
  double u = 0, v = 0;
};

struct LimitStencils {
  Stencil position, du, dv;  // position weights sum to 1, derivative weights to 0
};

// Keeps a reference to the mesh: it must outlive the evaluator.
class LimitEvaluator {
 public:
  //! \throw InvalidInput when OpenSubdiv rejects the mesh's topology.
  LimitEvaluator(const SurfaceMesh& mesh, const SubdivisionOptions& opt);
  ~LimitEvaluator();
  LimitEvaluator(const LimitEvaluator&) = delete;
  LimitEvaluator& operator=(const LimitEvaluator&) = delete;

  const SurfaceMesh& mesh() const { return mesh_; }
  //! Empty when (face, u, v) can be evaluated; otherwise why not, with the valid range
  //! ("face 12 does not exist (0..99)", "u = 1.2 is outside [0, 1]", ...).
  std::string why_not(const FaceParameter& at) const;
  //! Vertex v as a corner (u, v at the domain's corner) of an incident face the evaluator
  //! takes (a quad under Catmull-Clark, a triangle under Loop); face -1 when there is none.
  FaceParameter at_vertex(int v) const;
  //! \throw InvalidInput (the text of why_not) for a point that cannot be evaluated.
  LimitStencils stencils(const FaceParameter& at) const;
  //! Applies stencils to the mesh's positions (or to `positions`, same vertex count).
  Vec3 position(const FaceParameter& at) const;
  static Vec3 apply(const Stencil& s, const MatrixX3& positions);

  //! The point of the limit surface closest to `p`: projected Gauss-Newton on (u, v) against
  //! the exact limit in each face, faces taken in order of the distance to the (padded) box of
  //! the control points their patch depends on, until that lower bound exceeds the best
  //! distance found. `hint` (a face, or -1: a curve's previous sample) is tried first.
  //! Not thread-safe (one face's surface is cached). \throw InvalidInput when a Catmull-Clark
  //! mesh has a face that is not a quad (use a level from 1 on), or a Loop mesh no triangle.
  FaceParameter closest_point(const Vec3& p, int hint = -1) const;

 private:
  //! Why an N-gon is refused, and where the point is one level finer.
  std::string non_quad_face(int face) const;
  struct Impl;
  const SurfaceMesh& mesh_;
  SubdivisionOptions opt_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fairshape
