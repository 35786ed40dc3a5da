// Energies whose Hessian couples a vertex's whole one-ring (the stretch + bend fit of
// Boier-Martin et al. §3.4, the umbrella thin plate UᵀU) have (valence + 1)² entries per
// vertex: a legal but extreme vertex (a fan of 50,000 triangles) would need 2.5e9 entries
// and overflow a 32-bit sparse matrix. Such meshes are refused up front, by name.
#pragma once

#include <string>

#include "fairshape/mesh/surface_mesh.h"

namespace fairshape {

//! The largest valence a ring-coupling energy accepts ((2049)² ≈ 4.2M entries, 67 MB of
//! triplets for that one vertex).
inline constexpr int kMaxCoupledValence = 2048;

//! \throw InvalidInput naming the vertex above kMaxCoupledValence, or the total count when
//! Σ (valence + 1)² exceeds what a 32-bit sparse matrix holds.
void check_ring_coupling(const SurfaceMesh& mesh, const std::string& energy);

}  // namespace fairshape
