// A multiresolution subdivision surface H = (M^0, ..., M^L): a base mesh, the subdivision
// operators S_l, and per-level detail vectors, so that
//     X_{l+1} = S_l X_l + D_{l+1}          (details in world coordinates), or
//     X_{l+1} = P + F(P) · D^loc_{l+1},  P = S_l X_l   (details in local frames),
// where F(P) holds, per vertex, the frame (t1, t2, n) of the predicted surface P: the limit
// normal n and the first edge projected onto the tangent plane (as in Zorin, Schröder and
// Sweldens 1997 and Khodakovsky & Schröder 1999). Local details follow the surface when a
// coarse level is edited; world details translate with it.
#pragma once

#include <string>
#include <vector>

#include "fairshape/core/backend.h"
#include "fairshape/core/error.h"
#include "fairshape/mesh/surface_mesh.h"
#include "fairshape/subdivision/scheme.h"
#include "fairshape/subdivision/subdivider.h"

namespace fairshape {

enum class DetailSpace { World, Local };

struct Frames {
  MatrixX3 t1, t2, n;  // orthonormal per row
};
//! Frames of a mesh from its limit normals; a vertex without a normal gets the world axes.
Frames local_frames(const SurfaceMesh& mesh, const SubdivisionOptions& opt);

class MultiresSurface {
 public:
  //! Zero details: every level is the subdivision of the one below (levels = 0: just the mesh).
  //! \throw InvalidInput when refine_uniform's estimate exceeds `limits`.
  MultiresSurface(const SurfaceMesh& base, const SubdivisionOptions& opt, int levels, Backend backend,
                  const UniformRefineLimits& limits = {});

  //! Analysis of a fine semi-regular mesh: `finest` gives the positions of the base refined
  //! `levels` times (vertex ids as subdivide produces them). Each coarser level is the
  //! least-squares fit through the subdivision operator, X_l = argmin ‖S_l X − X_{l+1}‖, and
  //! the details are the residuals, so synthesis reproduces `finest` (up to rounding).
  //! \throw InvalidInput when the sizes do not match or a fit is singular.
  static MultiresSurface analyze(const SurfaceMesh& base, const MatrixX3& finest, const SubdivisionOptions& opt,
                                 int levels, Backend backend);

  int levels() const { return static_cast<int>(meshes_.size()) - 1; }
  const SubdivisionOptions& options() const { return opt_; }
  const SurfaceMesh& mesh(int level) const { return meshes_.at(level); }
  const SparseMatrix& subdivision_operator(int level) const { return S_.at(level); }  // level -> level + 1
  //! Details of level l = 1..L, world or local coordinates.
  const MatrixX3& details(int level, DetailSpace space) const;

  void set_base_positions(const MatrixX3& X0);
  //! Replaces the positions of one level (an edit made there); synthesize_from(level, ...)
  //! then rebuilds the finer levels on top of it.
  void set_level_positions(int level, const MatrixX3& X);
  //! Replaces the positions of the vertices `rows` of one level (row i of X for rows[i]).
  void set_level_rows(int level, const std::vector<int>& rows, const MatrixX3& X);
  void set_details(int level, const MatrixX3& d, DetailSpace space);
  //! Recomputes levels 1..L from the base, keeping the details of `keep` fixed (the other
  //! representation is updated to match).
  void synthesize(DetailSpace keep) { synthesize_from(0, keep); }
  void synthesize_from(int level, DetailSpace keep);
  //! synthesize_from(level, keep) restricted to what a change of the vertices `changed` of
  //! `level` reaches: on each finer level the vertices whose subdivision stencil reads a
  //! changed vertex of the level above, and their one-ring (the local frames read it). Their
  //! positions and details become what synthesize_from gives (to rounding: the rows are summed
  //! in another order); every other vertex is left untouched, bit for bit. Returns the vertices
  //! recomputed per level (entry `level` = `changed`, coarser entries empty). Stops at level
  //! `through` (−1: the finest).
  std::vector<std::vector<int>> synthesize_region_from(int level, const std::vector<int>& changed, DetailSpace keep,
                                                       int through = -1);
  //! The operator mapping positions of level `from` to level `to` ≥ from: S_{to-1} ··· S_from.
  SparseMatrix prolongation(int from, int to) const;

  //! Stores every level as a block of a .vtm (point arrays `detail`, `detail_local`) plus a
  //! JSON sidecar with the scheme options; load checks that the stored levels are consistent.
  void save(const std::string& vtm_path) const;
  static MultiresSurface load(const std::string& vtm_path, Backend backend);
  //! The scheme options and depth a saved hierarchy declares (its JSON sidecar), without
  //! reading its levels. \throw InvalidInput / IOError for a .vtm that is not a saved hierarchy.
  struct Stored {
    SubdivisionOptions options;
    int levels = 0;
  };
  static Stored stored(const std::string& vtm_path);

 private:
  MultiresSurface() = default;
  SubdivisionOptions opt_;
  Backend backend_ = kFastestBackend;
  std::vector<SurfaceMesh> meshes_;
  std::vector<SparseMatrix> S_;
  std::vector<MatrixX3> world_, local_;  // index = level; entry 0 unused
  using RowMajorSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  std::vector<RowMajorSparse> S_rows_;   // S_ by rows, made on the first region synthesis
};

//! Boier-Martin et al.'s claim as a number: the RMS change of the local-frame detail vectors
//! from `before` to `after` (a re-analysed edit of it), relative to their RMS size before.
//! NaN for a hierarchy without details (no levels, or all details zero).
double relative_detail_change(const MultiresSurface& before, const MultiresSurface& after);

}  // namespace fairshape
