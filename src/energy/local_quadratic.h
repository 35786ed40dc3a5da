// The discrete stretch + bend energy of §3.4 (Boier-Martin et al.):
//   E(P) = Σ_i Σ_{j,k ∈ R(i)} E_ijk (P_j − P_i)ᵀ(P_k − P_i) = ½ Pᵀ H P,
//   E_ijk = α (D1j D1k + D2j D2k) + β (D3j D3k + 2 D4j D4k + D5j D5k).
// Per vertex this is Σ_m w_m (g_m · P)² with w = (α, α, β, 2β, β) and g_m the m-th divided
// difference as a row over {i} ∪ R(i), so H = 2 Σ_i Σ_m w_m g_mᵀ g_m.
#pragma once

#include <memory>
#include <vector>

#include "fairshape/core/backend.h"
#include "fairshape/core/types.h"
#include "fairshape/mesh/surface_mesh.h"

namespace fairshape {

struct StretchBendWeights {
  double alpha = 0.1;  // stretch (first derivatives)
  double beta = 1.0;   // bend (second derivatives)
};

struct LocalFit;
//! 2·scale·(α, α, β, 2β, β): the weights of the five squared divided differences in H.
Eigen::Vector<double, 5> term_weights(const StretchBendWeights& w, double scale);
//! G: 5 × (1 + |R|), rows g_m over (v, ring...): g_m[v] = −Σ_j D_mj, g_m[ring j] = D_mj.
Eigen::MatrixXd difference_rows(const LocalFit& fit);
//! The vertex ids G's columns refer to: v, then its ring.
std::vector<int> stencil(int v, const LocalFit& fit);

//! Adds scale × (vertex v's block of H) to `out`. \throw InvalidInput for a degenerate ring.
void add_vertex_block(const SurfaceMesh& mesh, int v, const StretchBendWeights& w, double scale, Triplets& out);
//! scale × H over all vertices: reference = one vertex after another; optimized = TBB chunks.
void add_stretch_bend_hessian(const SurfaceMesh& mesh, const StretchBendWeights& w, double scale, Triplets& out,
                              Backend backend);
//! scale × H; the optimized back end assembles compressed storage directly (gram_assembly.h).
SparseMatrix stretch_bend_hessian(const SurfaceMesh& mesh, const StretchBendWeights& w, double scale,
                                  Backend backend);
inline SparseMatrix stretch_bend_hessian(const SurfaceMesh& mesh, const StretchBendWeights& w, Backend backend) {
  return stretch_bend_hessian(mesh, w, 1.0, backend);
}

class Energy;
//! The registered stretch + bend energies without a config: of the deformed positions
//! (`surface_thin_plate`, §3.4) or of the deformation (`detail_preserving`, §4.1).
enum class StretchBendOf { Positions, Deformation };
std::unique_ptr<Energy> make_stretch_bend(StretchBendWeights w, StretchBendOf of, Backend backend);

}  // namespace fairshape
