// Rotation-aware detail preservation (beyond Boier-Martin et al.): the energy of the
// deformation of §4.1 measures every divided difference against the rest shape's, so a rigid
// rotation of a region costs energy and a large normal or curve edit shears the details. Here
// each vertex's rest derivatives may turn with the surface:
//   E_R(X) = Σ_i Σ_m w_m ‖g_m X − (g_m P) R_iᵀ‖²,   R_i ∈ SO(3),
// g_m the m-th divided difference of vertex i (local_quadratic.h), w = (α, α, β, 2β, β).
// With every R_i = I it is the energy of the deformation ΔP = X − P: the details in rotated
// local frames, solved by alternation in the manner of Sorkine and Alexa's "As-rigid-as-possible
// surface modeling":
//   local   R_i = the rotation that best turns vertex i's five weighted rest differences onto
//           the deformed ones (a Procrustes problem: the SVD of a 3 × 3 matrix);
//   global  the constrained quadratic problem with the same H and the linear term
//           b = 2 Σ_i Σ_m w_m g_mᵀ (g_m P)(R_iᵀ − I) — H does not change, so one factorization
//           serves every round.
// A rigid motion of the whole model is a fixed point with E_R = 0. Both steps are exact
// minimizers, so every round lowers E_R (a block descent); the rounds are accelerated with an
// energy safeguard (design/rotation_aware_edit.cpp) and stop on the size of their change.
#pragma once

#include <vector>

#include "fairshape/energy/local_quadratic.h"

namespace fairshape {

using Mat3 = Eigen::Matrix3d;

//! Exact: the rotation minimizing the vertex's share of E_R (a block-descent step).
//! TangentFrame: the rotation of its first differences (Q_u, Q_v) alone — no descent, but it
//! sees a turn about the normal that the heavier, nearly normal second differences mask.
enum class RotationFit { Exact, TangentFrame };

class LocalRotations {
 public:
  //! The divided differences of `rest` with the stretch + bend weights, scaled like the energy's H.
  LocalRotations(const SurfaceMesh& rest, const StretchBendWeights& w, double scale);
  //! The local step: per fit (a vertex, or a side of a crease), its rotation for the deformed positions X (n × 3).
  std::vector<Mat3> fit(const MatrixX3& deformed, RotationFit how = RotationFit::Exact) const;
  //! The global step's linear term (n × 3) for rotations R (one per fit, as fit() returns them): with it, ½ΔᵀHΔ − bᵀΔ equals E_R(P + Δ) up to a constant.
  Eigen::MatrixXd linear_term(const std::vector<Mat3>& R) const;
  //! The constant c(R) that completes the global step's quadratic: ½ΔᵀHΔ − bᵀΔ + c = E_R(P + Δ).
  double constant_term(const std::vector<Mat3>& R) const;
  //! E_R of the deformed positions with the rotations fit(deformed).
  double energy(const MatrixX3& deformed) const;

 private:
  struct Vertex {              // one fit: a vertex, or one side of a sharp crease through it
    double weight = 1.0;      // its share of the vertex's energy
    std::vector<int> ids;     // the vertex, then its ring
    Eigen::MatrixXd G;        // 5 × ids.size(): the divided differences as rows over ids
    Eigen::Matrix<double, 5, 3> rest;  // G P: the rest derivatives
  };
  std::vector<Vertex> vertices_;
  Eigen::Vector<double, 5> w_;
  int n_ = 0;
};

}  // namespace fairshape
