// The objective functions of Welch & Witkin §4.1 on a hierarchical B-spline surface, per
// coordinate, as ½ pᵀ H p (H the Hessian):
//   thin plate under tension (eq. 4)  Q = ∫ Σ_ij α_ij D_i w D_j w + β_ij (D_i D_j w)²,
//   rest shape (eq. 6)                Q = ½ (p − p̂)ᵀ H (p − p̂), linear term f = H p̂,
//   control-point displacement        Q = ½ |p − p̂|², which §4.1 criticizes (for comparison).
// The integral is exact: r+1 Gauss points per direction on every leaf cell (the integrand is a
// polynomial of degree ≤ 2r − 2 in each variable there).
#pragma once

#include <Eigen/Core>

#include "fairshape/bspline/hierarchical_surface.h"
#include "fairshape/core/backend.h"
#include "fairshape/core/types.h"

namespace fairshape::bspline {

struct TensionWeights {
  Eigen::Matrix2d alpha = Eigen::Matrix2d::Zero();      // stretching: symmetric PSD
  Eigen::Matrix2d beta = Eigen::Matrix2d::Ones();  // bending: symmetric, entries ≥ 0 (all ones: the thin plate)
};
//! \throw InvalidInput naming the offending entry (α not symmetric PSD, β negative or not symmetric).
void validate(const TensionWeights& w);

//! The weights that give, in base-span units, the energy `w` defines in the sheet's design
//! units (SheetShape::span_size h): α_ij h_u h_v / (h_i h_j), β_ij h_u h_v / (h_i h_j)².
TensionWeights in_span_units(const TensionWeights& w, const Eigen::Vector2d& span_size);

//! H of eq. 5 (Hessian of Q), the integral in the sheet's design units (SheetShape::span_size). Reference: per quadrature point outer products into triplets;
//! optimized: dense local matrices per leaf cell in parallel (TBB).
SparseMatrix thin_plate_hessian(const HierarchicalSurface& s, const TensionWeights& w, Backend backend);

//! K with KᵀK = H, the sum-of-squares form the QR-penalty solver factors instead of H (§4.3,
//! eq. 10): per leaf cell, the R of the QR of its quadrature rows (one per point and term).
SparseMatrix thin_plate_square_root(const HierarchicalSurface& s, const TensionWeights& w);

}  // namespace fairshape::bspline
