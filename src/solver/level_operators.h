// What a multilevel solver needs from a multiresolution representation: the prolongation of
// each level to the next (Catmull-Clark or Loop S_l, a polyline's synthesis with zero
// details) and, optionally, the energy re-assembled on each level. The representation knows
// nothing of solvers; the design layer fills this in (design/edit_solve.h).
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Dense>

#include "fairshape/core/types.h"

namespace fairshape {

//! Each vertex's star, CSR (`ids[offsets[v] .. offsets[v + 1])`, v itself included), and its
//! mean squared distance to the star's other vertices (h², a local mesh size).
struct VertexStars {
  std::vector<int> offsets, ids;
  std::vector<double> size2;
};

// Ids nest: vertex i of level l is vertex i of level l + 1 (subdivision keeps a vertex's id
// for its vertex point), which tells a solver which coarse unknowns a reduced system keeps.
struct LevelOperators {
  //! [l]: n_{l+1} × n_l; the last one ends at the level the system lives on.
  std::vector<SparseMatrix> prolongation;
  //! The energy's H on level l (n_l × n_l), for re-assembled coarse operators; may be empty.
  std::function<SparseMatrix(int level)> reassemble;
  //! [l], l = 0 .. prolongation.size(): vertices where the prolongation loses polynomial
  //! reproduction (extraordinary vertices of a subdivision scheme). Multigrid adds patch
  //! smoothing around them; may be empty.
  std::vector<std::vector<int>> singular;
  //! The stars of level l (for each vertex, the vertices of its faces), with a local mesh size:
  //! multigrid adds star patches where the energy is far stiffer than that size predicts
  //! (MultigridOptions::stiff_stars); may be empty.
  std::function<VertexStars(int level)> stars;
  //! The vertex positions of the level the system lives on (n × 3), for solvers that need the
  //! geometry (an algebraic multigrid's near-null space: constants and linear functions); may be empty.
  Eigen::MatrixXd positions;
  int coarse_levels() const { return static_cast<int>(prolongation.size()); }
};

//! Which unknowns of the finest level the solved system has: `kept` (a reduced system drops
//! the constrained vertices; empty = all) of the coordinates stacked in `blocks` blocks
//! ([Δx; Δy; Δz]: 3, each operator acting on every block).
struct LevelSelection {
  std::vector<int> kept;
  int blocks = 1;
};

}  // namespace fairshape
