// Discrete Laplacians of a polygon mesh (edge graph). L is symmetric negative semi-definite
// with L·1 = 0: (L u)_i = Σ_j w_ij (u_j − u_i).
#pragma once

#include "fairshape/mesh/surface_mesh.h"

namespace fairshape {

enum class LaplacianWeights { Uniform, Cotangent };

//! Cotangent weights are defined on triangles only; \throw InvalidInput otherwise.
SparseMatrix graph_laplacian(const SurfaceMesh& mesh, LaplacianWeights weights);
//! The umbrella operator: rows of the uniform Laplacian divided by the valence.
SparseMatrix umbrella_operator(const SurfaceMesh& mesh);

}  // namespace fairshape
