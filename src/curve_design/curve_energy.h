// Quadratic energies of a polyline's points for the length-preserving editor of Sauvage,
// Hahmann and Bonneau, "Length preserving multiresolution editing of curves" (§3).
//
// Every energy here is a sum of squared linear stencils, E(X) = Σ_k |Σ_j c_kj X_{p_kj} − o_k|²,
// where X is the N×3 point matrix and the offset o_k is zero or a point of the attracting
// curve (plus a constant, see CurveStencil). One description serves both solvers: the linearized Lagrange loop assembles
// H = 2 Σ c cᵀ and b = 2 Σ c o (so E = ½ XᵀHX − bᵀX + const per coordinate), and Ceres
// takes each stencil as a residual block.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "fairshape/core/registry.h"
#include "fairshape/core/types.h"

namespace fairshape {

struct CurveStencil {
  int size = 0;                      // points used (1..3)
  std::array<int, 3> points{};       // indices into the curve
  std::array<double, 3> coeffs{};
  int attractor_point = -1;          // offset o = A[attractor_point], or zero when −1
  // Added to the offset: the share of points held fixed outside a solve window (edit_window.h),
  // so a stencil that straddles the window's edge keeps its full value.
  Vec3 constant = Vec3::Zero();
};

class CurveEnergy {
 public:
  virtual ~CurveEnergy() = default;
  virtual std::vector<CurveStencil> stencils(int n_points, bool closed) const = 0;
};

using CurveEnergyRegistry = Registry<CurveEnergy>;
//! bending (§3's second differences), stretching (first differences), attractor_distance (D).
void register_curve_energies(CurveEnergyRegistry& r);

//! §3's bending stencils ¼(c[i−1] − 2c[i] + c[i+1]) (the registered "bending" energy).
std::vector<CurveStencil> bending_stencils(int n_points, bool closed);

//! Σ|stencil|² at X (attractor A supplies the offsets).
double stencil_energy(const std::vector<CurveStencil>& s, const MatrixX3& X, const MatrixX3& A);
//! H (N×N, shared by x, y, z) and the linear term b (N×3) of ½ XᵀHX − bᵀX.
SparseMatrix stencil_hessian(const std::vector<CurveStencil>& s, int n_points);
MatrixX3 stencil_linear_term(const std::vector<CurveStencil>& s, const MatrixX3& A);

}  // namespace fairshape
