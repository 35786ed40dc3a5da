// Local parameterization and divided differences of Boier-Martin, Ronfard and Bernardini,
// "Detail-preserving variational surface design with multiresolution constraints", §3.3
// (after Kobbelt's discrete fairing): around each vertex P_0 the one-ring R(0) (edge and face
// neighbours, in angular order) is laid out in the plane by a polar map, and a quadratic
//   Q(u,v) = Q + u Q_u + v Q_v + ½u² Q_uu + uv Q_uv + ½v² Q_vv
// is fitted in least squares; D = (ΦᵀΦ)⁻¹Φᵀ (5 × |R|) maps the differences P_j − P_0 to
// (Q_u, Q_v, Q_uu, Q_uv, Q_vv).
//
// Choices where the paper is silent (papers/boier-martin/README.md):
// - boundary vertices: the fan from one boundary neighbour to the other is an open sector that
//   keeps its true total angle (only a fan wider than 2π is scaled down); interior fans are
//   normalized to 2π. Normalizing boundary fans to π (Kobbelt's choice) maps a 90-degree
//   corner to 180 degrees and gives affine deformations of a flat sheet bending energy;
//   tests/unit/stretch_bend_test.cpp checks that they have none;
// - a rank-deficient fit (a boundary corner of one face has three neighbours; even the five
//   neighbours of a straight boundary vertex of a regular grid leave Φ with rank 4): the
//   paper says "least norm"; we take, among all least-squares fits, the one with the
//   smallest second-order part. It equals (ΦᵀΦ)⁻¹Φᵀ when Φ has full rank and, unlike plain
//   least norm, reproduces affine data exactly (an affine deformation of a flat sheet has
//   zero bending energy at every vertex);
// - degenerate rings (a zero-length edge, or zero total angle): InvalidInput naming the vertex;
// - sharp creases (SurfaceMesh edge sharpness > 0 at the mesh's level): the fit must not
//   reach across one, so sector_fits() splits the ring at the sharp edges and fits each
//   sector on its own, as an open fan (papers/boier-martin/README.md, "Creases").
#pragma once

#include <vector>

#include "fairshape/mesh/surface_mesh.h"

namespace fairshape {

struct LocalFit {
  std::vector<int> ring;  // R(i): neighbour vertex ids in angular order
  Eigen::MatrixXd D;      // 5 × |R|
  double weight = 1.0;    // share of the vertex's energy (1 / number of sectors)
};

//! Ordered one-ring of vertex v: edge neighbours with the other vertices of the faces between
//! them; interior rings are cyclic, boundary rings run from one boundary neighbour to the other.
//! `sharp_spokes` (optional) receives the ring positions of the edge neighbours joined to v
//! by a tagged sharp edge (sharpness > 0), in ring order.
std::vector<int> ordered_one_ring(const SurfaceMesh& mesh, int v, std::vector<int>* sharp_spokes = nullptr);
//! Polar-map coordinates (u_j, v_j) of the ring around v. \throw InvalidInput (degenerate ring).
Eigen::MatrixX2d polar_map(const SurfaceMesh& mesh, int v, const std::vector<int>& ring);
//! D for a design matrix Φ (|R| × 5), with the rank-deficient rule above.
Eigen::MatrixXd least_squares_operator(const Eigen::MatrixXd& Phi);
//! The divided-difference operator of vertex v over its whole ring, creases ignored (the
//! tangents of normal constraints). \throw InvalidInput for an isolated or degenerate vertex.
LocalFit local_fit(const SurfaceMesh& mesh, int v);
//! The fits the energy sums at v: local_fit() where no sharp edge splits the ring; otherwise
//! (two or more sharp edges at an interior vertex, one or more at a boundary vertex) one fit
//! per sector between consecutive sharp edges, both crease neighbours included, laid out as an
//! open fan, each weighted 1 / #sectors. A dart (one sharp edge inside) is smooth there, as
//! in the subdivision rules. \throw InvalidInput as local_fit().
std::vector<LocalFit> sector_fits(const SurfaceMesh& mesh, int v);

}  // namespace fairshape
